//! Drawing panels into an in-memory RGB image and saving it as PNG.

use std::fs::File;
use std::io::BufWriter;
use std::ops::Range;
use std::path::Path;

use plotters::coord::Shift;
use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::prelude::*;

use super::axis::{Scale, extent, label, log_label, padded};
use super::downsample::Segments;
use super::font::{FAMILY, ensure_registered};
use super::options::{PlotOptions, PlotReport};
use crate::error::{Error, Result};

/// Line colours (the "tab10" palette).
const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

/// One line of a panel.
pub(crate) struct Line {
    /// Legend label; `None` draws no legend entry.
    pub label: Option<String>,
    /// The points to draw.
    pub data: Segments,
}

/// One chart: axes, lines, point clouds and notes.
pub(crate) struct Panel {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub y_scale: Scale,
    pub lines: Vec<Line>,
    /// Drawn as dots (thinned phase curves).
    pub clouds: Vec<Vec<(f64, f64)>>,
    /// Single marked points (an orbit's start), coloured like the line or cloud of that index.
    pub markers: Vec<(f64, f64)>,
    /// One unit is as long on both axes (the ranges are widened to the panel's aspect).
    pub equal_axes: bool,
    /// Printed above the plotting area (the first few; all are returned in the report).
    pub notes: Vec<String>,
    /// Labelled curves left out of the legend ([`super::legend::cap_legend`]).
    pub legend_more: usize,
}

impl Panel {
    pub fn new(
        title: impl Into<String>,
        x_label: impl Into<String>,
        y_label: impl Into<String>,
    ) -> Self {
        Self {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            y_scale: Scale::Linear,
            lines: Vec::new(),
            clouds: Vec::new(),
            markers: Vec::new(),
            equal_axes: false,
            notes: Vec::new(),
            legend_more: 0,
        }
    }

    fn points(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.lines
            .iter()
            .flat_map(|l| l.data.points())
            .chain(self.clouds.iter().flatten().copied())
            .chain(self.markers.iter().copied())
    }
}

/// A whole image: a title over a grid of panels.
pub(crate) struct Figure {
    pub title: String,
    /// (rows, columns) of the panel grid.
    pub grid: (usize, usize),
    pub panels: Vec<Panel>,
}

/// Renders `panels` on a `grid` under `title` to the PNG at `path`; the report lists every note.
///
/// # Errors
/// As [`render`].
pub(crate) fn draw_figure(
    path: &Path,
    opts: &PlotOptions,
    title: String,
    grid: (usize, usize),
    panels: Vec<Panel>,
) -> Result<PlotReport> {
    let mut fig = Figure {
        title,
        grid,
        panels,
    };
    let notes = render(path, opts, &mut fig)?;
    Ok(PlotReport {
        path: path.to_path_buf(),
        notes,
    })
}

/// Checks the options, renders the figure and writes the PNG. Returns every note printed.
pub(crate) fn render(path: &Path, opts: &PlotOptions, fig: &mut Figure) -> Result<Vec<String>> {
    let plot_err = |message: String| Error::Plot {
        path: path.to_path_buf(),
        message,
    };
    check_options(path, opts)?;
    if let (Some(note), Some(first)) = (&opts.note, fig.panels.first_mut()) {
        first.notes.push(note.clone());
    }
    ensure_registered().map_err(|m| plot_err(m.to_owned()))?;
    let (w, h) = (opts.width, opts.height);
    let mut buf = vec![255u8; w as usize * h as usize * 3];
    {
        let backend =
            BitMapBackend::<plotters::backend::RGBPixel>::with_buffer_and_format(&mut buf, (w, h))
                .map_err(|e| plot_err(e.to_string()))?;
        let root = backend.into_drawing_area();
        root.fill(&WHITE).map_err(|e| plot_err(e.to_string()))?;
        let body = if fig.title.is_empty() {
            root.clone()
        } else {
            root.titled(&fig.title, (FAMILY, 26))
                .map_err(|e| plot_err(e.to_string()))?
        };
        let areas = body.split_evenly(fig.grid);
        for (area, panel) in areas.iter().zip(fig.panels.iter_mut()) {
            super::legend::cap_legend(panel);
            draw_panel(area, panel).map_err(plot_err)?;
        }
        root.present().map_err(|e| plot_err(e.to_string()))?;
    }
    write_png(path, &buf, w, h)?;
    Ok(fig.panels.iter().flat_map(|p| p.notes.clone()).collect())
}

fn check_options(path: &Path, opts: &PlotOptions) -> Result<()> {
    let ok = |v: u32| (200..=10_000).contains(&v);
    if ok(opts.width) && ok(opts.height) {
        Ok(())
    } else {
        Err(Error::PlotInput {
            path: path.to_path_buf(),
            message: format!(
                "image size {}x{} is outside 200..=10000 pixels",
                opts.width, opts.height
            ),
        })
    }
}

/// Largest magnitude an axis may reach: the drawing library's tick search does not end for
/// ranges near the largest `f64` (a free particle with an absurd step reaches 1.7e308).
const LARGEST_DRAWN: f64 = 1e300;

/// Whether the axis `lo..hi`, padded, stays within what can be drawn.
fn drawable_range(lo: f64, hi: f64) -> bool {
    let (a, b) = padded(lo, hi, Scale::Linear);
    (hi - lo).is_finite() && a.abs() <= LARGEST_DRAWN && b.abs() <= LARGEST_DRAWN
}

/// Chooses the axes (adding notes for degenerate data) and draws one panel.
fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    panel: &mut Panel,
) -> Result<(), String> {
    let mut scale = panel.y_scale;
    let mut y_ext = extent(panel.points().map(|p| p.1), scale);
    if y_ext.is_none() && scale == Scale::Log {
        scale = Scale::Linear;
        y_ext = extent(panel.points().map(|p| p.1), scale);
    }
    let x_ext = extent(panel.points().map(|p| p.0), Scale::Linear);
    let mut drawable = true;
    match (x_ext, y_ext) {
        (Some((x0, x1)), Some((y0, y1))) => {
            if !drawable_range(x0, x1) || !drawable_range(y0, y1) {
                panel.notes.push(format!(
                    "values beyond ±{LARGEST_DRAWN:e} are too large to draw"
                ));
                drawable = false;
            } else if y0 == y1 {
                panel.notes.push(format!("constant: every value is {y0}"));
            }
        }
        _ => {
            panel.notes.push("no finite data to draw".to_owned());
            drawable = false;
        }
    }
    let (x_ext, y_ext) = match (x_ext, y_ext, drawable) {
        (Some(x), Some(y), true) => (x, y),
        _ => ((0.0, 1.0), (0.0, 1.0)),
    };
    let (mut x0, mut x1) = padded(x_ext.0, x_ext.1, Scale::Linear);
    let (mut y0, mut y1) = padded(y_ext.0, y_ext.1, scale);
    if panel.equal_axes && drawable && scale == Scale::Linear {
        ((x0, x1), (y0, y1)) = equalised((x0, x1), (y0, y1), plot_pixels(area, panel));
    }
    match scale {
        Scale::Linear => draw_chart(area, panel, drawable, x0..x1, y0..y1, &|v: &f64| {
            label(*v, y0, y1)
        }),
        Scale::Log => draw_chart(
            area,
            panel,
            drawable,
            x0..x1,
            (y0..y1).log_scale(),
            &|v: &f64| log_label(*v),
        ),
    }
}

/// The approximate size in pixels of a panel's plotting area (the layout of [`draw_chart`]).
fn plot_pixels<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, panel: &Panel) -> (f64, f64) {
    let (w, h) = area.dim_in_pixel();
    let title = if panel.title.is_empty() { 0 } else { 30 };
    let notes = 18 * panel.notes.len().min(4) as u32 + 8;
    let width = w.saturating_sub(96 + 24).max(1);
    let height = h.saturating_sub(title + notes + 50 + 16).max(1);
    (f64::from(width), f64::from(height))
}

/// Widens the shorter of two ranges about its centre so one unit spans as many pixels on
/// both axes of a `pixels.0 × pixels.1` area.
fn equalised(x: (f64, f64), y: (f64, f64), pixels: (f64, f64)) -> ((f64, f64), (f64, f64)) {
    let per_pixel = ((x.1 - x.0) / pixels.0).max((y.1 - y.0) / pixels.1);
    let widen = |(lo, hi): (f64, f64), px: f64| {
        let (mid, half) = (0.5 * (lo + hi), 0.5 * per_pixel * px);
        if half.is_finite() && half > 0.0 {
            (mid - half, mid + half)
        } else {
            (lo, hi)
        }
    };
    (widen(x, pixels.0), widen(y, pixels.1))
}

fn draw_chart<DB, Y>(
    area: &DrawingArea<DB, Shift>,
    panel: &Panel,
    drawable: bool,
    x: Range<f64>,
    y: Y,
    y_fmt: &dyn Fn(&f64) -> String,
) -> Result<(), String>
where
    DB: DrawingBackend,
    Y: AsRangedCoord<Value = f64>,
    Y::CoordDescType: ValueFormatter<f64>,
{
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    let (xl, xh) = (x.start, x.end);
    // Layout, top to bottom: panel title, notes, chart. Notes never hide data.
    const NOTE_LINE: i32 = 18;
    let below_title = if panel.title.is_empty() {
        area.clone()
    } else {
        area.titled(&panel.title, (FAMILY, 20)).map_err(e)?
    };
    // At most MAX_NOTES lines; the full list is in the PlotReport.
    const MAX_NOTES: usize = 4;
    let mut shown: Vec<String> = panel.notes.iter().take(MAX_NOTES).cloned().collect();
    if panel.notes.len() > MAX_NOTES {
        shown[MAX_NOTES - 1] = format!("… and {} more notes", panel.notes.len() - MAX_NOTES + 1);
    }
    let note_band = NOTE_LINE * shown.len() as i32;
    let (notes_area, chart_area) = below_title.split_vertically(note_band + 8);
    let style = TextStyle::from((FAMILY, 14).into_font()).color(&RGBColor(150, 20, 20));
    for (i, note) in shown.iter().enumerate() {
        notes_area
            .draw_text(note, &style, (12, 6 + NOTE_LINE * i as i32))
            .map_err(e)?;
    }
    let mut chart = ChartBuilder::on(&chart_area)
        .margin(12)
        .margin_top(4)
        .x_label_area_size(50)
        .y_label_area_size(96)
        .build_cartesian_2d(x, y)
        .map_err(e)?;
    chart
        .configure_mesh()
        .x_desc(panel.x_label.as_str())
        .y_desc(panel.y_label.as_str())
        .label_style((FAMILY, 14))
        .axis_desc_style((FAMILY, 16))
        .x_labels(8)
        .y_labels(8)
        .x_label_formatter(&|v: &f64| label(*v, xl, xh))
        .y_label_formatter(y_fmt)
        .bold_line_style(RGBColor(215, 215, 215))
        .light_line_style(RGBColor(240, 240, 240))
        .draw()
        .map_err(e)?;

    let mut legend = false;
    if drawable {
        for (k, line) in panel.lines.iter().enumerate() {
            let color = PALETTE[k % PALETTE.len()];
            // 1-px lines: plotters polygonizes wider paths, which loses sharp spikes
            // (a min/max-reduced series is made of them).
            let style = color.stroke_width(1);
            for (s, seg) in line.data.segments.iter().enumerate() {
                if seg.len() == 1 {
                    chart
                        .draw_series(seg.iter().map(|&p| Circle::new(p, 2, color.filled())))
                        .map_err(e)?;
                    continue;
                }
                let drawn = chart
                    .draw_series(LineSeries::new(seg.iter().copied(), style))
                    .map_err(e)?;
                if let (0, Some(name)) = (s, &line.label) {
                    legend = true;
                    drawn
                        .label(name)
                        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], style));
                }
            }
        }
        if panel.legend_more > 0 {
            legend = true;
            chart
                .draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())
                .map_err(e)?
                .label(super::legend::more_text(panel.legend_more))
                .legend(|(x, y)| EmptyElement::at((x, y)));
        }
        for (k, cloud) in panel.clouds.iter().enumerate() {
            let color = PALETTE[k % PALETTE.len()];
            chart
                .draw_series(cloud.iter().map(|&p| Circle::new(p, 1, color.filled())))
                .map_err(e)?;
        }
        for (k, &p) in panel.markers.iter().enumerate() {
            let color = PALETTE[k % PALETTE.len()];
            chart
                .draw_series(std::iter::once(Circle::new(p, 5, color.filled())))
                .map_err(e)?;
        }
    }
    if legend {
        chart
            .configure_series_labels()
            .label_font((FAMILY, 14))
            .background_style(WHITE.mix(0.85))
            .border_style(RGBColor(160, 160, 160))
            .position(SeriesLabelPosition::UpperRight)
            .draw()
            .map_err(e)?;
    }

    Ok(())
}

/// Writes the PNG; a write that fails part-way (a full disk) removes what it left, so no empty
/// or truncated picture stands where a plot should be.
fn write_png(path: &Path, rgb: &[u8], w: u32, h: u32) -> Result<()> {
    let written = encode_png(path, rgb, w, h);
    if written.is_err() {
        let _ = std::fs::remove_file(path);
    }
    written
}

fn encode_png(path: &Path, rgb: &[u8], w: u32, h: u32) -> Result<()> {
    let file = File::create(path).map_err(|e| Error::io("create", path, e))?;
    let mut encoder = png::Encoder::new(BufWriter::new(file), w, h);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let png_err = |e: png::EncodingError| match e {
        png::EncodingError::IoError(io) => Error::io("write to", path, io),
        other => Error::Plot {
            path: path.to_path_buf(),
            message: other.to_string(),
        },
    };
    let mut writer = encoder.write_header().map_err(png_err)?;
    writer.write_image_data(rgb).map_err(png_err)?;
    writer.finish().map_err(png_err)
}
