//! Heat maps of a sweep's output (`klaw plot-sweep`): one result column over two swept
//! parameters, a cell per (x, y) value pair, coloured on a viridis scale with a colour bar;
//! points that failed are light grey with a dark cross.
//!
//! Cells span halfway to the neighbouring values (so uneven grids are drawn to scale), and the
//! axes' ticks are the swept values themselves, at the cells' centres: a tick per value, labelled
//! as many as fit without overlapping (the first always), each label the value with the fewest
//! decimals that all the axis's values need. When the
//! sweep varies other parameters too, several rows fall on one cell: the cell shows the mean
//! over its converged rows (for `converged`, the fraction converged over all its rows), and is
//! failed when none of its rows converged. (x, y) pairs without any row are left white.
//!
//! PNG or SVG by the extension, 1200 × 900 px, written whole or not at all; text needs the
//! font of [`crate::plot`] and is left out without one.
use std::collections::BTreeMap;
use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::error::{Error, Result};
use crate::model::attributes::AttributeTable;
use crate::model::{InputError, error::Reason};
use crate::plot::{self, Chart, Draw, DrawError, Drawn, FONT, Png, TITLE_SIZE, msg, titled};
use crate::sweep::RowFormat;
use crate::sweep::output::LineError;

/// Heat map size in pixels (width, height).
pub const HEAT_MAP_SIZE: (u32, u32) = (1200, 900);
/// Fill of a failed cell (a dark cross is drawn over it).
pub const FAILED_COLOR: RGBColor = RGBColor(200, 200, 200);
const CROSS_COLOR: RGBColor = RGBColor(60, 60, 60);
/// Fill of a converged cell without a value of the column.
const NO_VALUE_COLOR: RGBColor = RGBColor(235, 235, 235);

/// Short names accepted for `--column`.
pub(crate) const COLUMN_ALIASES: [(&str, &str); 3] = [
    ("iterations", "mean_iterations"),
    ("iterations_mean", "mean_iterations"),
    ("peak_knee", "max_peak_swing_knee_flexion_deg"),
];

/// One cell of the map.
#[derive(Clone, Debug, PartialEq)]
pub struct MapCell {
    /// The cell's value of the x column.
    pub x: f64,
    /// The cell's value of the y column.
    pub y: f64,
    /// Rows on this cell, and how many converged.
    pub rows: usize,
    /// Rows on this cell whose walk converged.
    pub converged: usize,
    /// The mean of the column over the converged rows (the fraction converged for `converged`).
    pub value: Option<f64>,
    /// Pixel rectangle (left, top, right, bottom) in the figure, once drawn.
    pub pixels: (i32, i32, i32, i32),
}

impl MapCell {
    /// Whether no walk of the cell converged (drawn in [`FAILED_COLOR`]).
    pub fn failed(&self) -> bool {
        self.converged == 0
    }
}

/// A tick of a heat map's axis: one swept value.
#[derive(Clone, Debug, PartialEq)]
pub struct Tick {
    /// The swept value.
    pub value: f64,
    /// Its pixel along the axis (the column of an x tick, the row of a y tick), at the centre of
    /// its cells.
    pub pixel: i32,
    /// The label, when there is room for it.
    pub label: Option<String>,
    /// The label's box (left, top, right, bottom) in the figure's pixels, when labelled.
    pub label_box: Option<(i32, i32, i32, i32)>,
}

/// The data of a heat map.
#[derive(Clone, Debug, PartialEq)]
pub struct HeatMap {
    /// The column along the horizontal axis.
    pub x: String,
    /// The column along the vertical axis.
    pub y: String,
    /// The column the cells are coloured by.
    pub column: String,
    /// The distinct values of x, increasing.
    pub xs: Vec<f64>,
    /// The distinct values of y, increasing.
    pub ys: Vec<f64>,
    /// One cell per (x, y) pair found in the rows.
    pub cells: Vec<MapCell>,
    /// The ticks of the horizontal axis, one per value of `xs`, once drawn.
    pub x_ticks: Vec<Tick>,
    /// The ticks of the vertical axis, one per value of `ys`, once drawn.
    pub y_ticks: Vec<Tick>,
}

fn bad(parameter: &str, reason: String) -> Error {
    InputError::bad_value(parameter, reason).into()
}

/// The unit of a column of a sweep output ("" for none).
pub(crate) fn unit(name: &str) -> String {
    let u = match name {
        "velocity" | "achieved_velocity" => "m/s",
        "step_length"
        | "achieved_step_length"
        | "height"
        | "mean_hip_excursion"
        | "min_toe_clearance" => "m",
        "step_frequency" | "achieved_step_frequency" => "steps/min",
        "mass" => "kg",
        "mass_per_height2" => "kg/m²",
        "max_peak_swing_knee_flexion_deg" => "°",
        "stance_pct" | "double_support_pct" => "% of the cycle",
        "mean_iterations" | "max_iterations" => "trials per solve",
        "converged" => "fraction of the cell's walks",
        "work_per_m" => "J/m",
        "work_per_kg_m" => "J/(kg·m)",
        _ => {
            return AttributeTable::builtin()
                .0
                .get(name)
                .map(|a| match a.unit.as_str() {
                    "1" => String::new(),
                    "deg" => "°".to_string(),
                    u => u.to_string(),
                })
                .unwrap_or_default();
        }
    };
    u.to_string()
}

/// "name (unit)" or "name".
fn label(name: &str) -> String {
    match unit(name).as_str() {
        "" => name.to_string(),
        u => format!("{name} ({u})"),
    }
}

/// One cell's text as a number: empty → none, true/false → 1/0.
fn number(text: &str) -> std::result::Result<Option<f64>, ()> {
    match text.trim() {
        "" => Ok(None),
        "true" => Ok(Some(1.0)),
        "false" => Ok(Some(0.0)),
        t => t.parse::<f64>().map(Some).map_err(|_| ()),
    }
}

/// The rows of a sweep output as (column name → cell text), CSV or JSON Lines by extension.
fn read_rows(path: &Path) -> Result<(Vec<String>, Vec<Vec<String>>)> {
    let format = RowFormat::from_path(path)?;
    let malformed =
        |reason: Reason| Error::from(InputError::malformed("sweep output", path, reason));
    let text = std::fs::read_to_string(path).map_err(|e| Error::Io {
        action: "reading",
        path: path.to_path_buf(),
        source: e,
    })?;
    match format {
        RowFormat::Csv => {
            let mut r = csv::Reader::from_reader(text.as_bytes());
            let header: Vec<String> = r
                .headers()
                .map_err(|e| malformed(Box::new(e)))?
                .iter()
                .map(str::to_string)
                .collect();
            let rows = r
                .records()
                .map(|rec| {
                    rec.map(|r| r.iter().map(str::to_string).collect())
                        .map_err(|e| malformed(Box::new(e)))
                })
                .collect::<Result<Vec<Vec<String>>>>()?;
            Ok((header, rows))
        }
        RowFormat::Jsonl => {
            let mut header: Vec<String> = Vec::new();
            let mut rows = Vec::new();
            for (i, line) in text
                .lines()
                .enumerate()
                .filter(|(_, l)| !l.trim().is_empty())
            {
                let map: serde_json::Map<String, serde_json::Value> = serde_json::from_str(line)
                    .map_err(|e| {
                        let reason = Box::new(e);
                        malformed(Box::new(LineError {
                            line: i + 1,
                            reason,
                        }))
                    })?;
                if header.is_empty() {
                    header = map.keys().cloned().collect();
                }
                rows.push(
                    header
                        .iter()
                        .map(|k| match map.get(k) {
                            None | Some(serde_json::Value::Null) => String::new(),
                            Some(serde_json::Value::String(s)) => s.clone(),
                            Some(v) => v.to_string(),
                        })
                        .collect(),
                );
            }
            Ok((header, rows))
        }
    }
}

/// The cells of the rows (axis columns `ix`, `iy`, value column `ic`, `converged` column
/// `iconv`), sorted by y then x: rows on one (x, y) pair share a cell, whose value is the mean
/// over its converged rows (over all its rows for `converged`).
fn cells(
    path: &Path,
    header: &[String],
    rows: &[Vec<String>],
    [ix, iy, ic, iconv]: [usize; 4],
    column: &str,
) -> Result<Vec<MapCell>> {
    let mut grid: BTreeMap<(u64, u64), MapCell> = BTreeMap::new();
    let mut sums: BTreeMap<(u64, u64), (f64, usize)> = BTreeMap::new();
    for (i, row) in rows.iter().enumerate() {
        let line = i + 2;
        let axis = |flag: &str, k: usize| match number(&row[k]) {
            Ok(Some(v)) if v.is_finite() => Ok(v),
            _ => Err(bad(
                flag,
                format!(
                    "column `{}` has `{}` in row {line} of {}: an axis needs a number in every \
                     row (was it swept?)",
                    header[k],
                    row[k],
                    path.display()
                ),
            )),
        };
        let (xv, yv) = (axis("x", ix)?, axis("y", iy)?);
        let converged = row[iconv] == "true";
        let value = number(&row[ic]).map_err(|_| {
            bad(
                "column",
                format!(
                    "column `{column}` is not numeric (`{}` in row {line})",
                    row[ic]
                ),
            )
        })?;
        // -0.0 and 0.0 are one value
        let key = ((xv + 0.0).to_bits(), (yv + 0.0).to_bits());
        let cell = grid.entry(key).or_insert(MapCell {
            x: xv,
            y: yv,
            rows: 0,
            converged: 0,
            value: None,
            pixels: (0, 0, 0, 0),
        });
        cell.rows += 1;
        cell.converged += usize::from(converged);
        let counts = column == "converged" || converged;
        if let (true, Some(v)) = (counts, value.filter(|v| v.is_finite())) {
            let s = sums.entry(key).or_insert((0.0, 0));
            s.0 += v;
            s.1 += 1;
        }
    }
    let mut cells: Vec<MapCell> = grid
        .into_iter()
        .map(|(key, mut c)| {
            c.value = sums.get(&key).map(|(s, n)| s / *n as f64);
            c
        })
        .collect();
    cells.sort_by(|a, b| a.y.total_cmp(&b.y).then(a.x.total_cmp(&b.x)));
    Ok(cells)
}

impl HeatMap {
    /// Read `column` over (`x`, `y`) from a sweep output. Unknown names, an axis equal to the
    /// other, axis columns with empty or non-numeric cells and non-numeric columns are input
    /// errors naming the flag and the available columns.
    pub fn read(path: &Path, x: &str, y: &str, column: &str) -> Result<HeatMap> {
        let column = COLUMN_ALIASES
            .iter()
            .find(|(alias, _)| *alias == column)
            .map_or(column, |(_, name)| name);
        let (header, rows) = read_rows(path)?;
        crate::sweep::rows::check_sweep_columns(&header)
            .map_err(|reason| InputError::malformed("sweep output", path, reason))?;
        if rows.is_empty() {
            let reason = "no rows after the header: nothing to draw";
            return Err(InputError::malformed("sweep output", path, reason).into());
        }
        let find = |flag: &str, name: &str| {
            header.iter().position(|h| h == name).ok_or_else(|| {
                bad(
                    flag,
                    format!(
                        "no column `{name}` in {}; its columns: {}",
                        path.display(),
                        header.join(", ")
                    ),
                )
            })
        };
        let (ix, iy, ic) = (find("x", x)?, find("y", y)?, find("column", column)?);
        let iconv = header
            .iter()
            .position(|h| h == "converged")
            .ok_or_else(|| {
                let reason = "no `converged` column: not written by klaw sweep";
                InputError::malformed("sweep output", path, reason)
            })?;
        if ix == iy {
            return Err(bad(
                "y",
                format!("`{y}` is also the x axis: give two parameters"),
            ));
        }
        // the sweep's text columns, whatever their cells (`error` is empty where all converged);
        // a text cell of any other column is refused by `cells`
        if matches!(column, "error" | "style") {
            let reason = format!(
                "`{column}` is not numeric (it holds text): choose a numeric column, e.g. \
                 converged, mean_iterations or achieved_velocity"
            );
            return Err(bad("column", reason));
        }
        let cells = cells(path, &header, &rows, [ix, iy, ic, iconv], column)?;
        let distinct = |f: &dyn Fn(&MapCell) -> f64| {
            let mut v: Vec<f64> = cells.iter().map(f).collect();
            v.sort_by(f64::total_cmp);
            v.dedup();
            v
        };
        let (xs, ys) = (distinct(&|c| c.x), distinct(&|c| c.y));
        Ok(HeatMap {
            x: x.to_string(),
            y: y.to_string(),
            column: column.to_string(),
            xs,
            ys,
            cells,
            x_ticks: Vec::new(),
            y_ticks: Vec::new(),
        })
    }

    /// The range of the colour scale: [0, 1] for `converged`, else the values' extent (widened
    /// when they are all equal).
    pub(crate) fn value_range(&self) -> (f64, f64) {
        if self.column == "converged" {
            return (0.0, 1.0);
        }
        let values = self.cells.iter().filter_map(|c| c.value);
        let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
        if !lo.is_finite() {
            (0.0, 1.0)
        } else if hi - lo < 1e-12 * lo.abs().max(1.0) {
            (lo - 0.5 * lo.abs().max(1.0), hi + 0.5 * hi.abs().max(1.0))
        } else {
            (lo, hi)
        }
    }

    /// Draw the map to `path` (PNG or SVG by extension); the cells' pixel rectangles are filled
    /// in.
    pub(crate) fn write(&mut self, path: &Path) -> Result<()> {
        let format = plot::figure_format(path)?;
        let text = plot::text_available();
        plot::write_figure(
            &mut MapDrawing { map: self, text },
            path,
            format,
            HEAT_MAP_SIZE,
            Png::Default,
            "the heat map",
        )
    }

    fn title(&self) -> String {
        let failed = self.cells.iter().filter(|c| c.failed()).count();
        let rows: usize = self.cells.iter().map(|c| c.rows).sum();
        let per_cell = if rows > self.cells.len() {
            let walks_failed: usize = self.cells.iter().map(|c| c.rows - c.converged).sum();
            format!(
                ", mean of ≤ {} walks per cell, {walks_failed} of {rows} walks failed",
                self.cells.iter().map(|c| c.rows).max().unwrap_or(1)
            )
        } else {
            String::new()
        };
        format!(
            "{} over {} × {}: {} points, {failed} failed (grey ×){per_cell}",
            self.column,
            self.x,
            self.y,
            self.cells.len()
        )
    }

    /// The map: title, cells on their value's colour (failed ones grey with a cross), colour bar.
    fn draw<DB: DrawingBackend>(&mut self, root: &DrawingArea<DB, Shift>, text: bool) -> Drawn {
        root.fill(&WHITE).map_err(msg)?;
        let area = titled(root, &self.title(), TITLE_SIZE, text)?;
        let (w, _) = area.dim_in_pixel();
        let (main, bar) = area.split_horizontally(w - if text { 190 } else { 80 });
        if self.cells.is_empty() {
            return Ok(());
        }
        let (xe, ye) = (cell_edges(&self.xs), cell_edges(&self.ys));
        let mut b = ChartBuilder::on(&main);
        b.margin(14);
        if text {
            b.x_label_area_size(56).y_label_area_size(80);
        }
        let mut chart = b
            .build_cartesian_2d(xe[0]..xe[xe.len() - 1], ye[0]..ye[ye.len() - 1])
            .map_err(msg)?;
        let mut mesh = chart.configure_mesh();
        // the ticks are the swept values, drawn below: none of plotters' round numbers
        mesh.disable_mesh().x_labels(0).y_labels(0);
        if text {
            mesh.x_desc(label(&self.x))
                .y_desc(label(&self.y))
                .label_style((FONT, 16))
                .axis_desc_style((FONT, 18));
        }
        mesh.draw().map_err(msg)?;
        let (lo, hi) = self.value_range();
        let index = |v: &[f64], x: f64| v.partition_point(|a| *a < x);
        for cell in &mut self.cells {
            let (i, j) = (index(&self.xs, cell.x), index(&self.ys, cell.y));
            let color = match cell.value {
                _ if cell.failed() => FAILED_COLOR,
                Some(v) => viridis((v - lo) / (hi - lo)),
                None => NO_VALUE_COLOR,
            };
            let corners = ((xe[i], xe[i + 1]), (ye[j], ye[j + 1]));
            cell.pixels = draw_cell(&mut chart, corners, color, cell.failed())?;
        }
        let ((x_lo, _), (y_lo, _)) = ((xe[0], 0.0), (ye[0], 0.0));
        let x_px: Vec<i32> = self
            .xs
            .iter()
            .map(|&x| chart.backend_coord(&(x, y_lo)).0)
            .collect();
        let y_px: Vec<i32> = self
            .ys
            .iter()
            .map(|&y| chart.backend_coord(&(x_lo, y)).1)
            .collect();
        let (left, bottom) = chart.backend_coord(&(x_lo, y_lo));
        self.x_ticks = draw_ticks(root, &self.xs, &x_px, Axis::X(bottom), text)?;
        self.y_ticks = draw_ticks(root, &self.ys, &y_px, Axis::Y(left), text)?;
        self.colour_bar(&bar, text, (lo, hi))
    }

    fn colour_bar<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        text: bool,
        (lo, hi): (f64, f64),
    ) -> Drawn {
        let mut b = ChartBuilder::on(area);
        b.margin_top(14)
            .margin_bottom(14 + 56)
            .margin_right(if text { 70 } else { 14 });
        if text {
            b.y_label_area_size(70);
        }
        let mut chart = b.build_cartesian_2d(0.0..1.0, lo..hi).map_err(msg)?;
        let mut mesh = chart.configure_mesh();
        mesh.disable_mesh().disable_x_axis();
        if text {
            mesh.y_desc(label(&self.column))
                .label_style((FONT, 15))
                .axis_desc_style((FONT, 16));
        }
        mesh.draw().map_err(msg)?;
        const STEPS: usize = 200;
        chart
            .draw_series((0..STEPS).map(|k| {
                let (a, b) = (k as f64 / STEPS as f64, (k + 1) as f64 / STEPS as f64);
                Rectangle::new(
                    [(0.0, lo + a * (hi - lo)), (1.0, lo + b * (hi - lo))],
                    viridis(0.5 * (a + b)).filled(),
                )
            }))
            .map_err(msg)?;
        Ok(())
    }
}

/// Tick marks' lengths (px): every value's, and a labelled one's.
const TICK_PX: i32 = 4;
const LABELLED_TICK_PX: i32 = 8;
/// The gap between the tick and its label, and the least gap between two labels (px).
const LABEL_GAP_PX: i32 = 4;
const LABEL_SPACING_PX: i32 = 10;
const TICK_FONT: i32 = 16;

/// A heat map's axis and where it lies: the row of the horizontal axis or the column of the
/// vertical one (the figure's pixels).
#[derive(Clone, Copy)]
enum Axis {
    X(i32),
    Y(i32),
}

/// The fewest decimals (at most 6) that show every one of `values` to 1e-9 of its size.
fn decimals(values: &[f64]) -> usize {
    let need = |v: f64| {
        (0..=6)
            .find(|&d| {
                let scale = 10f64.powi(d as i32);
                ((v * scale).round() / scale - v).abs() <= 1e-9 * v.abs().max(1.0)
            })
            .unwrap_or(6)
    };
    values.iter().map(|&v| need(v)).max().unwrap_or(0)
}

/// A tick on `axis` at every value of `values` (`pixels` along the axis), outside the plotting
/// area; with text, labels left to right (bottom to top) wherever one clears the last labelled,
/// the first always.
fn draw_ticks<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    values: &[f64],
    pixels: &[i32],
    axis: Axis,
    text: bool,
) -> std::result::Result<Vec<Tick>, DrawError> {
    use plotters::style::text_anchor::{HPos, Pos, VPos};
    let d = decimals(values);
    let pos = match axis {
        Axis::X(_) => Pos::new(HPos::Center, VPos::Top),
        Axis::Y(_) => Pos::new(HPos::Right, VPos::Center),
    };
    let style = TextStyle::from((FONT, TICK_FONT)).color(&BLACK).pos(pos);
    let mut ticks = Vec::with_capacity(values.len());
    // the end of the last label along the axis: its right edge (x) or its top (y)
    let mut last_end: Option<i32> = None;
    for (&value, &p) in values.iter().zip(pixels) {
        let label = format!("{value:.d$}");
        let label_box = if text {
            let (w, h) = root.estimate_text_size(&label, &style).map_err(msg)?;
            let (w, h) = (w as i32, h as i32);
            let (lbox, start, end) = match axis {
                Axis::X(row) => {
                    let top = row + LABELLED_TICK_PX + LABEL_GAP_PX;
                    (
                        (p - w / 2, top, p - w / 2 + w, top + h),
                        p - w / 2,
                        p - w / 2 + w,
                    )
                }
                // along y the pixels fall upwards: "start" is the bottom, as a negative row
                Axis::Y(col) => {
                    let right = col - LABELLED_TICK_PX - LABEL_GAP_PX;
                    (
                        (right - w, p - h / 2, right, p - h / 2 + h),
                        -(p - h / 2 + h),
                        -(p - h / 2),
                    )
                }
            };
            let clear = last_end.is_none_or(|e| start >= e + LABEL_SPACING_PX);
            clear.then(|| {
                last_end = Some(end);
                lbox
            })
        } else {
            None
        };
        let len = if label_box.is_some() {
            LABELLED_TICK_PX
        } else {
            TICK_PX
        };
        let mark = match axis {
            Axis::X(row) => [(p, row), (p, row + len)],
            Axis::Y(col) => [(col - len, p), (col, p)],
        };
        root.draw(&PathElement::new(mark.to_vec(), BLACK.stroke_width(1)))
            .map_err(msg)?;
        if let Some((l, t, r, b)) = label_box {
            let at = match axis {
                Axis::X(_) => ((l + r) / 2, t),
                Axis::Y(_) => (r, (t + b) / 2),
            };
            root.draw(&Text::new(label.clone(), at, style.clone()))
                .map_err(msg)?;
        }
        ticks.push(Tick {
            value,
            pixel: p,
            label: label_box.map(|_| label),
            label_box,
        });
    }
    Ok(ticks)
}

/// The edges of the cells around sorted distinct values: halfway to each neighbour, the outer
/// cells as wide as their inner halves (a single value: ±10 % of it, at least ±0.1 / 2).
fn cell_edges(v: &[f64]) -> Vec<f64> {
    let half = |i: usize| 0.5 * (v[i + 1] - v[i]);
    let n = v.len();
    let mut e = Vec::with_capacity(n + 1);
    let first_gap = if n > 1 {
        half(0)
    } else {
        0.5 * v[0].abs().max(1.0) * 0.1
    };
    e.push(v[0] - first_gap);
    e.extend(v.windows(2).map(|p| 0.5 * (p[0] + p[1])));
    let last_gap = if n > 1 { half(n - 2) } else { first_gap };
    e.push(v[n - 1] + last_gap);
    e
}

/// One cell over ((x0, x1), (y0, y1)), with the cross of a failed one; its pixel rectangle.
fn draw_cell<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    ((x0, x1), (y0, y1)): ((f64, f64), (f64, f64)),
    color: RGBColor,
    failed: bool,
) -> std::result::Result<(i32, i32, i32, i32), DrawError> {
    chart
        .draw_series(std::iter::once(Rectangle::new(
            [(x0, y1), (x1, y0)],
            color.filled(),
        )))
        .map_err(msg)?;
    if failed {
        // the cross, inset a little from the corners
        let (dx, dy) = (0.15 * (x1 - x0), 0.15 * (y1 - y0));
        chart
            .draw_series([
                PathElement::new(
                    vec![(x0 + dx, y0 + dy), (x1 - dx, y1 - dy)],
                    CROSS_COLOR.stroke_width(2),
                ),
                PathElement::new(
                    vec![(x0 + dx, y1 - dy), (x1 - dx, y0 + dy)],
                    CROSS_COLOR.stroke_width(2),
                ),
            ])
            .map_err(msg)?;
    }
    let (l, t) = chart.backend_coord(&(x0, y1));
    let (r, b) = chart.backend_coord(&(x1, y0));
    Ok((l, t, r, b))
}

struct MapDrawing<'a> {
    map: &'a mut HeatMap,
    text: bool,
}

impl Draw for MapDrawing<'_> {
    type Output = ();
    fn draw<DB: DrawingBackend>(&mut self, root: &DrawingArea<DB, Shift>) -> Drawn {
        self.map.draw(root, self.text)
    }
}

/// The viridis colour map at s ∈ [0, 1] (clamped), interpolated linearly between 9 samples of
/// matplotlib's table.
pub(crate) fn viridis(s: f64) -> RGBColor {
    const TABLE: [(u8, u8, u8); 9] = [
        (68, 1, 84),
        (71, 44, 122),
        (59, 81, 139),
        (44, 113, 142),
        (33, 144, 141),
        (39, 173, 129),
        (92, 200, 99),
        (170, 220, 50),
        (253, 231, 37),
    ];
    let s = if s.is_finite() {
        s.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let x = s * (TABLE.len() - 1) as f64;
    let i = (x.floor() as usize).min(TABLE.len() - 2);
    let u = x - i as f64;
    let mix = |a: u8, b: u8| (f64::from(a) + u * (f64::from(b) - f64::from(a))).round() as u8;
    let (a, b) = (TABLE[i], TABLE[i + 1]);
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// Read a sweep output and write the heat map of `column` over (`x`, `y`) to `out`.
pub fn heat_map(input: &Path, x: &str, y: &str, column: &str, out: &Path) -> Result<HeatMap> {
    plot::figure_format(out)?;
    let mut map = HeatMap::read(input, x, y, column)?;
    map.write(out)?;
    Ok(map)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn viridis_ends_and_failure_colour_is_off_the_scale() {
        assert_eq!(viridis(0.0), RGBColor(68, 1, 84));
        assert_eq!(viridis(1.0), RGBColor(253, 231, 37));
        assert_eq!(viridis(2.0), viridis(1.0));
        // grey is not on the scale: every scale colour differs from it by > 40 in some channel
        for k in 0..=1000 {
            let c = viridis(k as f64 / 1000.0);
            let d = [
                (c.0 as i32 - FAILED_COLOR.0 as i32).abs(),
                (c.1 as i32 - FAILED_COLOR.1 as i32).abs(),
                (c.2 as i32 - FAILED_COLOR.2 as i32).abs(),
            ];
            assert!(d.iter().any(|&x| x > 40), "{c:?}");
        }
    }

    #[test]
    fn units_of_columns_and_attributes() {
        assert_eq!(label("velocity"), "velocity (m/s)");
        assert_eq!(
            label("max_peak_swing_knee_flexion_deg"),
            "max_peak_swing_knee_flexion_deg (°)"
        );
        assert_eq!(label("bounciness"), "bounciness");
        assert_eq!(label("steps"), "steps");
    }
}
