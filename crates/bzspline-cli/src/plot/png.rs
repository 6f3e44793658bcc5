//! The figure as PNG (the SVG rasterised by resvg) and PDF (the same usvg tree
//! converted by svg2pdf).

#[cfg(any(feature = "png", feature = "pdf"))]
use std::sync::Arc;

use anyhow::anyhow;
#[cfg(any(feature = "png", feature = "pdf"))]
use anyhow::Context as _;

use super::{render_svg, PlotData, PlotOptions};

/// The figure as a PNG: [`render_svg`] rasterised by resvg at
/// [`PlotOptions::png_scale`] pixels per SVG pixel, with text in a system font.
///
/// # Errors
///
/// Fails when no font is installed (the figure's text could not be drawn; on
/// Debian or Ubuntu `apt-get install fonts-dejavu-core` provides one), when the
/// scaled size is out of range, or if encoding fails.
pub fn render_png(data: &[PlotData], opts: &PlotOptions) -> anyhow::Result<Vec<u8>> {
    let svg = render_svg(data, opts);
    svg_to_png(&svg, opts.png_scale)
}

/// Rasterises an SVG document at `scale` pixels per SVG pixel.
///
/// # Errors
///
/// As [`render_png`].
#[cfg(not(feature = "png"))]
pub fn svg_to_png(_svg: &str, _scale: f32) -> anyhow::Result<Vec<u8>> {
    Err(anyhow!(
        "this bzspline was built without PNG output (cargo feature `png`); write SVG instead"
    ))
}

/// Rasterises an SVG document at `scale` pixels per SVG pixel.
///
/// # Errors
///
/// As [`render_png`].
#[cfg(feature = "png")]
pub fn svg_to_png(svg: &str, scale: f32) -> anyhow::Result<Vec<u8>> {
    use resvg::tiny_skia;
    if !(scale.is_finite() && scale > 0.0 && scale <= 16.0) {
        return Err(anyhow!("PNG scale {scale} is outside (0, 16]"));
    }
    let tree = figure_tree(svg)?;
    let size = tree
        .size()
        .to_int_size()
        .scale_by(scale)
        .context("PNG size out of range")?;
    let mut pixmap =
        tiny_skia::Pixmap::new(size.width(), size.height()).context("PNG size out of range")?;
    resvg::render(
        &tree,
        tiny_skia::Transform::from_scale(scale, scale),
        &mut pixmap.as_mut(),
    );
    pixmap.encode_png().context("encoding the PNG")
}

/// The figure's SVG parsed by usvg with a system font for its text: the tree
/// both the PNG and the PDF are drawn from.
///
/// # Errors
///
/// No font installed, or SVG that does not parse.
#[cfg(any(feature = "png", feature = "pdf"))]
pub fn figure_tree(svg: &str) -> anyhow::Result<resvg::usvg::Tree> {
    use resvg::usvg;
    let mut db = usvg::fontdb::Database::new();
    db.load_system_fonts();
    if db.is_empty() {
        return Err(anyhow!(
            "no fonts found for the figure's text; install one \
             (Debian/Ubuntu: apt-get install fonts-dejavu-core) or write SVG instead"
        ));
    }
    db.set_sans_serif_family("DejaVu Sans");
    let opt = usvg::Options {
        fontdb: Arc::new(db),
        font_family: "DejaVu Sans".into(),
        ..usvg::Options::default()
    };
    usvg::Tree::from_str(svg, &opt).context("parsing the figure's SVG")
}

/// The figure as a PDF: [`render_svg`] converted by svg2pdf, vector graphics
/// with the text's font embedded, one page the figure's size.
///
/// # Errors
///
/// As [`figure_tree`], or a failed conversion.
#[cfg(feature = "pdf")]
pub fn render_pdf(data: &[PlotData], opts: &PlotOptions) -> anyhow::Result<Vec<u8>> {
    let tree = figure_tree(&render_svg(data, opts))?;
    svg2pdf::to_pdf(
        &tree,
        svg2pdf::ConversionOptions::default(),
        svg2pdf::PageOptions::default(),
    )
    .map_err(|e| anyhow!("converting the figure to PDF: {e}"))
}

/// As the `pdf` feature's [`render_pdf`].
///
/// # Errors
///
/// Always: this build has no PDF output.
#[cfg(not(feature = "pdf"))]
pub fn render_pdf(_data: &[PlotData], _opts: &PlotOptions) -> anyhow::Result<Vec<u8>> {
    Err(anyhow!(
        "this bzspline was built without PDF output (cargo feature `pdf`); write SVG instead"
    ))
}

#[cfg(all(test, feature = "png"))]
mod tests {
    use super::*;
    use crate::plot::tests::example;

    #[test]
    fn png_has_the_requested_size() {
        let opts = PlotOptions {
            width: 320,
            height: 200,
            png_scale: 1.5,
            ..PlotOptions::default()
        };
        match render_png(&[example(2, 0.5)], &opts) {
            Ok(png) => {
                assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
                // IHDR: width and height, big-endian, at bytes 16..24.
                assert_eq!(&png[16..24], &[0, 0, 1, 224, 0, 0, 1, 44]);
            }
            // A machine without any font: the error says what to install.
            Err(e) => assert!(e.to_string().contains("fonts-dejavu-core"), "{e:#}"),
        }
        assert!(svg_to_png("<svg", 1.0).is_err());
        assert!(render_png(
            &[],
            &PlotOptions {
                png_scale: f32::NAN,
                ..PlotOptions::default()
            }
        )
        .is_err());
    }
}
