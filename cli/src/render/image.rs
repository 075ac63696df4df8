//! An 8-bit sRGB image and its PNG encoding.

use std::io::Write;
use std::path::Path;

use crate::atomic::write_atomic;
use crate::error::Result;

/// An RGB image, 8 bits per channel, sRGB-encoded, rows top to bottom.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width * height` pixels of 3 bytes (red, green, blue), row after row
    /// from the top.
    pub rgb: Vec<u8>,
}

impl Image {
    /// The pixel at column `x`, row `y` (from the top).
    ///
    /// # Panics
    ///
    /// If the pixel is outside the image.
    pub fn pixel(&self, x: u32, y: u32) -> [u8; 3] {
        assert!(x < self.width && y < self.height, "pixel outside the image");
        let k = 3 * (y as usize * self.width as usize + x as usize);
        [self.rgb[k], self.rgb[k + 1], self.rgb[k + 2]]
    }

    /// Writes the image as PNG (8-bit RGB, marked sRGB). The same image
    /// always gives the same bytes.
    pub fn write_png(&self, out: &mut dyn Write) -> std::io::Result<()> {
        let mut encoder = png::Encoder::new(out, self.width, self.height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
        let mut writer = encoder.write_header().map_err(std::io::Error::other)?;
        writer
            .write_image_data(&self.rgb)
            .map_err(std::io::Error::other)?;
        writer.finish().map_err(std::io::Error::other)
    }

    /// Writes the image as PNG to `path`, atomically.
    pub fn save_png(&self, path: &Path) -> Result<()> {
        write_atomic(path, |out| self.write_png(out))
    }
}

/// Linear value in `[0, 1]` (clamped) to an 8-bit sRGB code.
pub fn linear_to_srgb8(v: f32) -> u8 {
    let v = v.clamp(0.0, 1.0);
    let s = if v <= 0.003_130_8 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    };
    (s * 255.0 + 0.5).floor() as u8
}

/// An 8-bit sRGB code to a linear value in `[0, 1]`.
pub fn srgb8_to_linear(code: u8) -> f32 {
    let s = f32::from(code) / 255.0;
    if s <= 0.040_45 {
        s / 12.92
    } else {
        ((s + 0.055) / 1.055).powf(2.4)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_round_trips_and_has_known_points() {
        assert_eq!(linear_to_srgb8(0.0), 0);
        assert_eq!(linear_to_srgb8(1.0), 255);
        assert_eq!(linear_to_srgb8(2.0), 255);
        // Linear 0.5 is sRGB 0.7354 -> 188.
        assert_eq!(linear_to_srgb8(0.5), 188);
        for code in 0..=255u8 {
            assert_eq!(linear_to_srgb8(srgb8_to_linear(code)), code);
        }
    }

    #[test]
    fn png_decodes_to_the_same_pixels() {
        let image = Image {
            width: 2,
            height: 1,
            rgb: vec![1, 2, 3, 250, 251, 252],
        };
        let mut bytes = Vec::new();
        image.write_png(&mut bytes).unwrap();
        let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
        let mut reader = decoder.read_info().unwrap();
        let mut buf = vec![0; reader.output_buffer_size()];
        let info = reader.next_frame(&mut buf).unwrap();
        assert_eq!((info.width, info.height), (2, 1));
        assert_eq!(&buf[..info.buffer_size()], &image.rgb[..]);
        assert_eq!(image.pixel(1, 0), [250, 251, 252]);
    }
}
