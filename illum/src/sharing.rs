//! The 1992 paper's vertex-sharing rules: how to evaluate one light's
//! irradiance at a vertex from the classes of the fragments around it.
//!
//! | classes around the vertex | plan |
//! |---|---|
//! | all lit | [`VertexPlan::Unoccluded`] |
//! | all umbra | [`VertexPlan::Zero`] |
//! | all penumbra | [`VertexPlan::VisiblePart`] |
//! | lit + penumbra | [`VertexPlan::Unoccluded`]: the vertex touches the lit region, so the whole light is visible; no visibility test |
//! | penumbra + umbra | [`VertexPlan::VisiblePart`]: evaluated, not promoted to umbra |
//! | lit + umbra (+ penumbra) | [`VertexPlan::Split`]: one value per side, the whole light on the lit side (lit and penumbra fragments), zero on the umbra side, so the boundary stays sharp |

use crate::error::IllumError;

/// The class of a fragment for one light.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum FragmentClass {
    /// Sees all of the light.
    Lit,
    /// Sees part of it.
    Penumbra,
    /// Sees none of it.
    Umbra,
}

/// How to obtain one fragment's value at the vertex.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum VertexValue {
    /// Irradiance from the whole light, with no visibility test.
    Unoccluded,
    /// Irradiance from the visible part of the light.
    VisiblePart,
    /// Zero, with nothing evaluated.
    Zero,
}

/// The evaluation plan for a vertex.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum VertexPlan {
    /// One value, from the whole light, shared by every fragment.
    Unoccluded,
    /// One value, from the visible part of the light.
    VisiblePart,
    /// One value, zero.
    Zero,
    /// Two values: the whole light for lit and penumbra fragments, zero for
    /// umbra fragments.
    Split,
}

impl VertexPlan {
    /// What a fragment of class `class` takes at this vertex.
    pub fn value_for(self, class: FragmentClass) -> VertexValue {
        match self {
            VertexPlan::Unoccluded => VertexValue::Unoccluded,
            VertexPlan::VisiblePart => VertexValue::VisiblePart,
            VertexPlan::Zero => VertexValue::Zero,
            VertexPlan::Split => match class {
                FragmentClass::Umbra => VertexValue::Zero,
                FragmentClass::Lit | FragmentClass::Penumbra => VertexValue::Unoccluded,
            },
        }
    }

    /// Whether the plan needs the visible part of the light.
    pub fn needs_visibility(self) -> bool {
        self == VertexPlan::VisiblePart
    }

    /// How many distinct values the vertex carries (1, or 2 for
    /// [`VertexPlan::Split`]).
    pub fn values(self) -> usize {
        if self == VertexPlan::Split { 2 } else { 1 }
    }
}

/// The plan for a vertex surrounded by fragments of the given classes (in
/// any order, repeats allowed); an error when there are none.
pub fn vertex_plan<I>(classes: I) -> Result<VertexPlan, IllumError>
where
    I: IntoIterator<Item = FragmentClass>,
{
    let (mut lit, mut pen, mut umb) = (false, false, false);
    for c in classes {
        match c {
            FragmentClass::Lit => lit = true,
            FragmentClass::Penumbra => pen = true,
            FragmentClass::Umbra => umb = true,
        }
    }
    Ok(match (lit, pen, umb) {
        (false, false, false) => return Err(IllumError::NoFragments),
        (true, _, true) => VertexPlan::Split,
        (true, _, false) => VertexPlan::Unoccluded,
        (false, true, _) => VertexPlan::VisiblePart,
        (false, false, true) => VertexPlan::Zero,
    })
}

#[cfg(test)]
mod tests {
    use super::FragmentClass::*;
    use super::*;

    #[test]
    fn rules() {
        assert_eq!(vertex_plan([Lit, Lit]), Ok(VertexPlan::Unoccluded));
        assert_eq!(vertex_plan([Umbra]), Ok(VertexPlan::Zero));
        assert_eq!(
            vertex_plan([Penumbra, Penumbra]),
            Ok(VertexPlan::VisiblePart)
        );
        assert_eq!(vertex_plan([Penumbra, Lit]), Ok(VertexPlan::Unoccluded));
        assert_eq!(vertex_plan([Umbra, Penumbra]), Ok(VertexPlan::VisiblePart));
        assert_eq!(vertex_plan([Lit, Umbra]), Ok(VertexPlan::Split));
        assert_eq!(vertex_plan([Umbra, Penumbra, Lit]), Ok(VertexPlan::Split));
        assert_eq!(vertex_plan([]), Err(IllumError::NoFragments));
    }

    #[test]
    fn split_keeps_sides_apart() {
        let p = VertexPlan::Split;
        assert_eq!(p.value_for(Lit), VertexValue::Unoccluded);
        assert_eq!(p.value_for(Penumbra), VertexValue::Unoccluded);
        assert_eq!(p.value_for(Umbra), VertexValue::Zero);
        assert_eq!(p.values(), 2);
        assert!(!p.needs_visibility());
        assert!(VertexPlan::VisiblePart.needs_visibility());
        // Penumbra next to umbra is evaluated, not promoted to umbra.
        assert_eq!(
            VertexPlan::VisiblePart.value_for(Umbra),
            VertexValue::VisiblePart
        );
    }
}
