//! The candidate occluders between a point and an area light, gathered
//! from the scene BSP (the 1992 paper's analytic visibility for penumbra
//! vertices starts here).
//!
//! Only polygons that can cut the convex hull of the point and the light
//! matter. A BSP node whose plane leaves that hull wholly on one side sends
//! the search down that side only, and its own polygons (which lie in the
//! plane) cannot reach the hull. The test is `f64` with a generous margin
//! towards "both sides": a spurious candidate only costs a clipping that
//! removes nothing, a missed one would be wrong. Coordinates are the BSP's
//! grid units.

use crate::area_light::AreaLight;
use crate::vec3::Vec3;
use bsp_core::{SceneBsp, SceneChild};

/// Indices (into [`SceneBsp::polygons`]) of the polygons that may lie
/// between `p` and `light`, in the BSP's order. The caller drops the
/// polygon `p` lies on, if any.
pub fn occluders_between(bsp: &SceneBsp, p: Vec3, light: &AreaLight) -> Vec<u32> {
    let mut out = Vec::new();
    let mut stack = vec![bsp.root()];
    let points: Vec<Vec3> = std::iter::once(p)
        .chain(light.vertices().iter().copied())
        .collect();
    while let Some(child) = stack.pop() {
        let SceneChild::Node(i) = child else { continue };
        let node = &bsp.nodes()[i as usize];
        let [a, b, c, d] = node.plane.approx();
        let (mut front, mut back) = (false, false);
        for x in &points {
            let value = a * x[0] + b * x[1] + c * x[2] + d;
            // Far above the rounding of this sum (its terms' magnitude times
            // a few ulps), so only a clear sign counts.
            let margin = 1e-9
                * (a.abs() * x[0].abs() + b.abs() * x[1].abs() + c.abs() * x[2].abs() + d.abs());
            if value > margin {
                front = true;
            } else if value < -margin {
                back = true;
            } else {
                front = true;
                back = true;
            }
        }
        if front && back {
            out.extend(node.polygons.clone());
        }
        if front {
            stack.push(node.front);
        }
        if back {
            stack.push(node.back);
        }
    }
    out.sort_unstable();
    out
}
