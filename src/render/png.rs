//! PNG pictures: the SVG picture rasterized with resvg, so both formats show the same.

use anyhow::{Context, Result};
use resvg::{tiny_skia, usvg};

use super::{RenderOptions, Renderer, Svg};
use crate::layout::Layout;

/// The longest side of a PNG, pixels: larger floors are drawn at a smaller scale.
const MAX_SIDE: f32 = 4096.0;
/// Oversampling of the SVG's 40 px/m for small floors (80 px/m).
const OVERSAMPLE: f32 = 2.0;

/// The PNG renderer.
#[derive(Debug, Clone, Copy, Default)]
pub struct Png;

impl Renderer for Png {
    fn render(&self, layout: &Layout, options: &RenderOptions) -> Result<Vec<u8>> {
        let svg = Svg.render(layout, options)?;
        let tree = usvg::Tree::from_data(&svg, &usvg::Options::default())
            .context("rasterizing the SVG picture")?;
        let size = tree.size();
        let scale = OVERSAMPLE.min(MAX_SIDE / size.width().max(size.height()));
        let width = (size.width() * scale).ceil().max(1.0) as u32;
        let height = (size.height() * scale).ceil().max(1.0) as u32;
        let mut pixmap = tiny_skia::Pixmap::new(width, height)
            .with_context(|| format!("a {width}x{height} picture is too large"))?;
        resvg::render(
            &tree,
            tiny_skia::Transform::from_scale(scale, scale),
            &mut pixmap.as_mut(),
        );
        pixmap.encode_png().context("encoding the PNG")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::Algorithm;
    use crate::layout::{GenerateSpec, build_layout};
    use crate::maze::Grid;

    #[test]
    fn the_png_shows_the_pure_colours() {
        let layout = build_layout(&GenerateSpec::course(
            Grid::new(9, 9).unwrap(),
            Algorithm::Dfs,
            42,
        ))
        .unwrap();
        let bytes = Png.render(&layout, &RenderOptions::default()).unwrap();
        assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
        let pixmap = tiny_skia::Pixmap::decode_png(&bytes).unwrap();
        assert_eq!((pixmap.width(), pixmap.height()), (800, 800));
        let pixel = |x: f64, y: f64| {
            // Floor metres to pixels: 80 px/m, origin in the middle, y down.
            let px = ((x + 5.0) * 80.0) as u32;
            let py = ((5.0 - y) * 80.0) as u32;
            let p = pixmap.pixel(px, py).unwrap();
            (p.red(), p.green(), p.blue())
        };
        let start = &layout.start.pose;
        assert_eq!(pixel(start.x + 0.3, start.y + 0.3), (0, 0, 255));
        let end = &layout.end.pose;
        assert_eq!(pixel(end.x + 0.3, end.y - 0.3), (255, 0, 0));
        let line = layout
            .segments
            .iter()
            .find(|s| {
                let far =
                    |p: &crate::layout::Pose| (s.x - p.x).abs() > 0.8 || (s.y - p.y).abs() > 0.8;
                far(start) && far(end)
            })
            .unwrap();
        assert_eq!(pixel(line.x, line.y), (0, 255, 0));
    }
}
