//! Dependency-free SVG line plots: work-precision diagrams (log-log), time
//! traces (linear) and multi-panel figures. The output is plain SVG 1.1 that
//! browsers and rsvg render; no fonts, scripts or CSS are required.

use std::fmt::Write as _;
use std::path::Path;

const W: f64 = 640.0;
const H: f64 = 420.0;
const PALETTE: [&str; 8] = [
    "#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#17becf",
];
/// SVG cannot measure text, so layout uses an average 12px sans-serif glyph width.
const CHAR_W: f64 = 6.8;

pub struct Series {
    pub label: String,
    pub points: Vec<(f64, f64)>,
    pub markers: bool,
}

pub struct Plot {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub log_x: bool,
    pub log_y: bool,
    pub series: Vec<Series>,
}

impl Series {
    pub fn line(label: &str, points: Vec<(f64, f64)>) -> Self {
        Series {
            label: label.to_string(),
            points,
            markers: false,
        }
    }

    pub fn with_markers(self) -> Self {
        Series {
            markers: true,
            ..self
        }
    }
}

impl Plot {
    /// Linear axes, no series.
    pub fn new(title: &str, x_label: &str, y_label: &str) -> Self {
        Plot {
            title: title.to_string(),
            x_label: x_label.to_string(),
            y_label: y_label.to_string(),
            log_x: false,
            log_y: false,
            series: Vec::new(),
        }
    }

    pub fn log_log(self) -> Self {
        Plot {
            log_x: true,
            log_y: true,
            ..self
        }
    }

    // The builder name is fixed by the callers' API; it is not `ops::Add`.
    #[allow(clippy::should_implement_trait)]
    pub fn add(mut self, series: Series) -> Self {
        self.series.push(series);
        self
    }

    /// One 640x420 panel as a complete SVG document.
    pub fn to_svg(&self) -> String {
        panels(std::slice::from_ref(self), 1)
    }

    pub fn write(&self, path: &Path) -> std::io::Result<()> {
        std::fs::write(path, self.to_svg())
    }

    /// Points that can be drawn on this plot's axes, with `None` marking a gap
    /// so a line is broken at a NaN (or non-positive value on a log axis)
    /// instead of silently bridging it.
    fn usable(&self, s: &Series) -> Vec<Option<(f64, f64)>> {
        s.points
            .iter()
            .map(|&(x, y)| (drawable(x, self.log_x) && drawable(y, self.log_y)).then_some((x, y)))
            .collect()
    }

    fn draw(&self, out: &mut String) {
        let pts: Vec<_> = self.series.iter().flat_map(|s| self.usable(s)).collect();
        let pts: Vec<(f64, f64)> = pts.into_iter().flatten().collect();
        let xa = Axis::new(pts.iter().map(|p| p.0), self.log_x);
        let ya = Axis::new(pts.iter().map(|p| p.1), self.log_y);
        // The left margin grows with the widest y tick label so it never hits the axis title.
        let widest = ya.ticks.iter().map(|t| t.1.len()).max().unwrap_or(1) as f64;
        let (left, right) = ((34.0 + widest * CHAR_W).max(56.0), W - 18.0);
        let (top, bottom) = (40.0, H - 52.0);

        let _ = writeln!(out, r#"<rect width="{W}" height="{H}" fill="white"/>"#);
        text(out, (W / 2.0, 24.0), TITLE, &self.title);
        for &m in &xa.minor {
            let x = xa.pos(m, left, right);
            line(out, (x, top), (x, bottom), MINOR);
        }
        for &m in &ya.minor {
            let y = ya.pos(m, bottom, top);
            line(out, (left, y), (right, y), MINOR);
        }
        for (t, label) in &xa.ticks {
            let x = xa.pos(*t, left, right);
            line(out, (x, top), (x, bottom), GRID);
            line(out, (x, bottom), (x, bottom + 4.0), DARK);
            text(out, (x, bottom + 17.0), MIDDLE, label);
        }
        for (t, label) in &ya.ticks {
            let y = ya.pos(*t, bottom, top);
            line(out, (left, y), (right, y), GRID);
            line(out, (left - 4.0, y), (left, y), DARK);
            text(out, (left - 7.0, y + 4.0), END, label);
        }
        rect(out, (left, top), (right - left, bottom - top), FRAME);
        text(out, ((left + right) / 2.0, H - 14.0), MIDDLE, &self.x_label);
        let yc = (top + bottom) / 2.0;
        let rotate = format!(r#"{MIDDLE} transform="rotate(-90 16 {yc})""#);
        text(out, (16.0, yc), &rotate, &self.y_label);

        let mut drawn = Vec::new(); // pixel positions, used to keep the legend off the data
        for (i, s) in self.series.iter().enumerate() {
            let colour = PALETTE[i % PALETTE.len()];
            let (px, py) = (
                |x| xa.pos(xa.map(x), left, right),
                |y| ya.pos(ya.map(y), bottom, top),
            );
            let to_px = |(x, y)| (px(x), py(y));
            let pixels: Vec<_> = self.usable(s).into_iter().map(|p| p.map(to_px)).collect();
            for run in pixels.split(Option::is_none).filter(|r| !r.is_empty()) {
                let run: Vec<(f64, f64)> = run.iter().flatten().copied().collect();
                if run.len() > 1 {
                    let pts: Vec<_> = run.iter().map(|(x, y)| format!("{x:.2},{y:.2}")).collect();
                    let pts = pts.join(" ");
                    let _ = writeln!(out, r#"<polyline points="{pts}" {STROKE}="{colour}"/>"#);
                    // Segment midpoints too, so sparse lines also repel the legend.
                    let mid = |w: &[(f64, f64)]| ((w[0].0 + w[1].0) / 2.0, (w[0].1 + w[1].1) / 2.0);
                    drawn.extend(run.windows(2).map(mid));
                }
                for &(x, y) in &run {
                    // A lone point between gaps would be invisible as a line, so always mark it.
                    if s.markers || run.len() == 1 {
                        marker(out, i, (x, y), colour);
                    }
                    drawn.push((x, y));
                }
            }
        }
        self.legend(out, [left, right, top, bottom], &drawn);
    }

    fn legend(&self, out: &mut String, frame: [f64; 4], drawn: &[(f64, f64)]) {
        if self.series.iter().all(|s| s.label.is_empty()) {
            return;
        }
        let [left, right, top, bottom] = frame;
        let chars = self.series.iter().map(|s| s.label.chars().count()).max();
        let w = 40.0 + chars.unwrap_or(0) as f64 * CHAR_W;
        let h = 8.0 + 17.0 * self.series.len() as f64;
        let (l, r, t, b) = (left + 8.0, right - w - 8.0, top + 8.0, bottom - h - 8.0);
        let hits = |&(cx, cy): &(f64, f64)| {
            let inside = |p: &&(f64, f64)| p.0 >= cx && p.0 <= cx + w && p.1 >= cy && p.1 <= cy + h;
            drawn.iter().filter(inside).count()
        };
        // min_by_key keeps the first of equals, so top-right wins ties.
        let corners = [(r, t), (l, t), (r, b), (l, b)];
        let (lx, ly) = corners.into_iter().min_by_key(hits).unwrap_or((r, t));
        rect(out, (lx, ly), (w, h), LEGEND);
        for (i, s) in self.series.iter().enumerate() {
            let (colour, y) = (PALETTE[i % PALETTE.len()], ly + 12.5 + 17.0 * i as f64);
            let style = format!(r#"{STROKE}="{colour}""#);
            line(out, (lx + 6.0, y), (lx + 28.0, y), &style);
            if s.markers {
                marker(out, i, (lx + 17.0, y), colour);
            }
            text(out, (lx + 33.0, y + 4.0), "", &s.label);
        }
    }
}

/// Several panels on a grid, `columns` wide, in one SVG document.
pub fn panels(plots: &[Plot], columns: usize) -> String {
    let columns = columns.max(1);
    let rows = plots.len().div_ceil(columns).max(1);
    let (w, h) = (W * columns.min(plots.len().max(1)) as f64, H * rows as f64);
    let mut out = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" version="1.1" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="DejaVu Sans, Arial, sans-serif" font-size="12">"#
    );
    for (i, p) in plots.iter().enumerate() {
        let (x, y) = (W * (i % columns) as f64, H * (i / columns) as f64);
        let _ = writeln!(out, r#"<g transform="translate({x},{y})">"#);
        p.draw(&mut out);
        out.push_str("</g>\n");
    }
    out.push_str("</svg>\n");
    out
}

pub fn write_panels(plots: &[Plot], columns: usize, path: &Path) -> std::io::Result<()> {
    std::fs::write(path, panels(plots, columns))
}

const TITLE: &str = r#" text-anchor="middle" font-size="15" font-weight="bold""#;
const MIDDLE: &str = r#" text-anchor="middle""#;
const END: &str = r#" text-anchor="end""#;
const FRAME: &str = r##"fill="none" stroke="#333""##;
const LEGEND: &str = r##"fill="white" fill-opacity="0.85" stroke="#999""##;
const MINOR: &str = r##"stroke="#f0f0f0""##;
const GRID: &str = r##"stroke="#d8d8d8""##;
const DARK: &str = r##"stroke="#333""##;
/// Shared data-line style; the colour attribute value follows it.
const STROKE: &str = r#"fill="none" stroke-width="1.6" stroke-linejoin="round" stroke"#;

// Writing into a `String` cannot fail, hence the ignored `fmt::Result`s below.
fn line(out: &mut String, (x1, y1): (f64, f64), (x2, y2): (f64, f64), style: &str) {
    let xy = format!(r#"x1="{x1:.2}" y1="{y1:.2}" x2="{x2:.2}" y2="{y2:.2}""#);
    let _ = writeln!(out, "<line {xy} {style}/>");
}

fn rect(out: &mut String, (x, y): (f64, f64), (w, h): (f64, f64), style: &str) {
    let xy = format!(r#"x="{x:.2}" y="{y:.2}" width="{w:.2}" height="{h:.2}""#);
    let _ = writeln!(out, "<rect {xy} {style}/>");
}

/// Escapes here, so no caller can forget to.
fn text(out: &mut String, (x, y): (f64, f64), attrs: &str, s: &str) {
    let xy = format!(r#"x="{x:.2}" y="{y:.2}""#);
    let _ = writeln!(out, "<text {xy}{attrs}>{}</text>", esc(s));
}

/// The 1e300 cap keeps padding and spans finite, so no inf/NaN reaches the output.
fn drawable(v: f64, log: bool) -> bool {
    v.is_finite() && v.abs() < 1e300 && (!log || v > 0.0)
}

/// Filled marker; the shape cycles with the series so lines stay apart in greyscale print.
fn marker(out: &mut String, i: usize, (x, y): (f64, f64), colour: &str) {
    let (r, q) = (3.8, 4.6);
    let corners: &[(f64, f64)] = match i % 4 {
        0 => &[],
        1 => &[(-r, -r), (r, -r), (r, r), (-r, r)],
        2 => &[(0.0, -q), (q, 0.0), (0.0, q), (-q, 0.0)],
        _ => &[(0.0, -q), (q, 0.8 * q), (-q, 0.8 * q)],
    };
    let _ = if corners.is_empty() {
        let c = format!(r#"cx="{x:.2}" cy="{y:.2}" r="{r}""#);
        writeln!(out, r#"<circle {c} fill="{colour}"/>"#)
    } else {
        let at = |(dx, dy): &(f64, f64)| format!("{:.2},{:.2}", x + dx, y + dy);
        let pts: Vec<String> = corners.iter().map(at).collect();
        let pts = pts.join(" ");
        writeln!(out, r#"<polygon points="{pts}" fill="{colour}"/>"#)
    };
}

fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// One axis; `lo`, `hi`, tick positions and `minor` are in plotting space
/// (log10 of the value on a log axis).
struct Axis {
    log: bool,
    lo: f64,
    hi: f64,
    ticks: Vec<(f64, String)>,
    minor: Vec<f64>,
}

impl Axis {
    fn new(values: impl Iterator<Item = f64>, log: bool) -> Axis {
        let (mut min, mut max) = (f64::INFINITY, f64::NEG_INFINITY);
        for v in values.map(|v| if log { v.log10() } else { v }) {
            (min, max) = (min.min(v), max.max(v));
        }
        if min > max {
            (min, max) = (0.0, 1.0); // nothing drawable: an empty unit frame
        }
        // A zero-width range would divide by zero; the relative 1e-12 also keeps
        // tick steps well above floating-point resolution.
        let pad = if max - min > 1e-12 * min.abs().max(max.abs()) {
            0.04 * (max - min)
        } else if log {
            0.5
        } else if min == 0.0 {
            1.0
        } else {
            0.1 * min.abs()
        };
        let (mut lo, mut hi) = (min - pad, max + pad);
        // With fewer than two decades inside, a log axis would be unlabelled: use whole decades.
        if log && hi.floor() - lo.ceil() < 1.0 {
            (lo, hi) = (lo.floor(), hi.ceil().max(lo.floor() + 1.0));
        }
        let (ticks, minor) = if log {
            (log_ticks(lo, hi), minor_log_ticks(lo, hi))
        } else {
            (linear_ticks(lo, hi), Vec::new())
        };
        Axis {
            log,
            lo,
            hi,
            ticks,
            minor,
        }
    }

    /// Data value to plotting space.
    fn map(&self, v: f64) -> f64 {
        if self.log {
            v.log10()
        } else {
            v
        }
    }

    /// Plotting-space value to a pixel between `a` (at `lo`) and `b` (at `hi`).
    fn pos(&self, t: f64, a: f64, b: f64) -> f64 {
        a + (t - self.lo) / (self.hi - self.lo) * (b - a)
    }
}

/// Ticks at 1, 2 or 5 times a power of ten, about five in the range.
fn linear_ticks(lo: f64, hi: f64) -> Vec<(f64, String)> {
    let raw = (hi - lo) / 5.0;
    let mag = 10f64.powf(raw.log10().floor());
    let nice = [1.0, 2.0, 5.0].into_iter().find(|m| raw < 1.5 * m * mag);
    let step = mag * nice.unwrap_or(10.0);
    let sci = lo.abs().max(hi.abs()) >= 1e5 || step < 1e-3;
    let decimals = (-step.log10().floor()).max(0.0) as usize;
    let mut ticks = Vec::new();
    for i in (lo / step).ceil() as i64..=(hi / step).floor() as i64 {
        let v = i as f64 * step;
        let v = if v.abs() < 1e-6 * step { 0.0 } else { v }; // no "-0"
        let label = if sci && v != 0.0 {
            sci_label(v)
        } else {
            format!("{v:.decimals$}")
        };
        ticks.push((v, label));
    }
    ticks
}

/// Whole decades in [lo, hi] (exponents), thinned to at most ~8 labels.
fn log_ticks(lo: f64, hi: f64) -> Vec<(f64, String)> {
    let (a, b) = (lo.ceil() as i32, hi.floor() as i32);
    let step = ((b - a) as f64 / 8.0).ceil().max(1.0) as usize;
    let label = |k: i32| match k {
        0 => "1".to_string(),
        1..=3 => 10i32.pow(k as u32).to_string(),
        _ => format!("1e{k}"),
    };
    (a..=b)
        .step_by(step)
        .map(|k| (k as f64, label(k)))
        .collect()
}

/// Unlabelled 2..9 grid lines inside each decade; skipped when too many to read.
fn minor_log_ticks(lo: f64, hi: f64) -> Vec<f64> {
    let mut minor = Vec::new();
    for d in lo.floor() as i32..hi.ceil() as i32 {
        let ms = (2..10).map(|m| d as f64 + (m as f64).log10());
        minor.extend(ms.filter(|p| *p > lo && *p < hi));
    }
    if hi - lo <= 8.0 {
        minor
    } else {
        Vec::new()
    }
}

/// Shortest scientific form ("2.5e-5"), hiding the round-off of `i * step`.
fn sci_label(v: f64) -> String {
    let s = format!("{v:.6e}");
    let (mant, exp) = s.split_once('e').unwrap_or((&s, "0"));
    format!("{}e{exp}", mant.trim_end_matches('0').trim_end_matches('.'))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(ticks: Vec<(f64, String)>) -> Vec<f64> {
        ticks.into_iter().map(|t| t.0).collect()
    }

    fn close(a: &[f64], b: &[f64]) -> bool {
        let near = |(x, y): (&f64, &f64)| (x - y).abs() < 1e-9 * (1.0 + y.abs());
        a.len() == b.len() && a.iter().zip(b).all(near)
    }

    /// Tags balance and close in order: a cheap stand-in for an XML parser.
    fn balanced(svg: &str) -> bool {
        let mut stack = Vec::new();
        for tag in svg.split('<').skip(1) {
            let tag = tag.split('>').next().unwrap_or("");
            let name = |t: &str| t.split_whitespace().next().map(str::to_string);
            if tag.starts_with('?') || tag.ends_with('/') {
                continue;
            } else if let Some(closing) = tag.strip_prefix('/') {
                if stack.pop() != Some(name(closing)) {
                    return false;
                }
            } else {
                stack.push(name(tag));
            }
        }
        stack.is_empty() && svg.matches('<').count() == svg.matches('>').count()
    }

    #[test]
    fn linear_ticks_use_1_2_5_steps() {
        let fine = [0.001, 0.0015, 0.002, 0.0025, 0.003, 0.0035, 0.004];
        assert!(close(
            &at(linear_ticks(0.0, 1.0)),
            &[0.0, 0.2, 0.4, 0.6, 0.8, 1.0]
        ));
        assert!(close(
            &at(linear_ticks(-3.0, 7.0)),
            &[-2.0, 0.0, 2.0, 4.0, 6.0]
        ));
        assert!(close(&at(linear_ticks(0.001, 0.0042)), &fine));
        assert!(close(
            &at(linear_ticks(-130.0, 370.0)),
            &[-100.0, 0.0, 100.0, 200.0, 300.0]
        ));
        let labels: Vec<String> = linear_ticks(-0.5, 0.5).into_iter().map(|t| t.1).collect();
        assert_eq!(labels, ["-0.4", "-0.2", "0.0", "0.2", "0.4"]);
        assert_eq!(linear_ticks(0.0, 5e-5)[1].1, "1e-5");
    }

    #[test]
    fn log_ticks_are_decades() {
        assert_eq!(at(log_ticks(-6.2, -1.9)), [-6.0, -5.0, -4.0, -3.0, -2.0]);
        assert_eq!(
            at(log_ticks(-20.0, 0.0)),
            [-20.0, -17.0, -14.0, -11.0, -8.0, -5.0, -2.0]
        );
        let labels: Vec<String> = log_ticks(-6.0, 2.0).into_iter().map(|t| t.1).collect();
        assert_eq!(
            labels,
            ["1e-6", "1e-5", "1e-4", "1e-3", "1e-2", "1e-1", "1", "10", "100"]
        );
        // Less than a decade of data still gets two labelled decades.
        let a = Axis::new([0.02, 0.05].into_iter(), true);
        assert_eq!((a.lo, a.hi, a.ticks.len()), (-2.0, -1.0, 2));
        assert_eq!(a.minor.len(), 8);
    }

    #[test]
    fn degenerate_ranges_are_padded() {
        for vals in [vec![3.0, 3.0], vec![0.0], vec![]] {
            let a = Axis::new(vals.into_iter(), false);
            assert!(a.hi > a.lo && !a.ticks.is_empty());
        }
        let a = Axis::new([1e-3].into_iter(), true);
        let f = a.pos(a.map(1e-3), 0.0, 1.0);
        assert!(a.hi > a.lo && f > 0.0 && f < 1.0);
    }

    #[test]
    fn svg_is_balanced_escaped_and_nan_free() {
        let rk4 = vec![(1e-3, 1e-2), (1e-2, 1e-6), (f64::NAN, 1.0), (0.1, 1e-10)];
        let euler = vec![(2e-3, 0.1), (0.0, 1.0), (-1.0, 5.0), (5e-2, 1e-3)];
        let wp = Plot::new("Work <precision> & cost", "CPU time [s]", "error")
            .log_log()
            .add(Series::line("RK4", rk4).with_markers())
            .add(Series::line("Euler", euler).with_markers());
        let flat = vec![(0.0, 1.0), (1.0, 1.0), (2.0, f64::INFINITY)];
        let flat = Plot::new("flat", "t", "u").add(Series::line("u", flat));
        let one = Plot::new("one point", "t", "u").add(Series::line("p", vec![(1.0, 2.0)]));
        let nan = Series::line("none", vec![(f64::NAN, f64::NAN)]);
        let empty = Plot::new("empty", "", "").add(nan);
        for svg in [wp.to_svg(), panels(&[wp, flat, one, empty], 2)] {
            assert!(balanced(&svg), "unbalanced SVG");
            assert!(!svg.contains("NaN") && !svg.contains("inf"));
            assert!(svg.contains("Work &lt;precision&gt; &amp; cost"));
        }
    }

    #[test]
    fn writes_files_even_with_nan_points() {
        let dir = std::env::temp_dir();
        let x = vec![(0.0, 0.0), (1.0, f64::NAN), (2.0, 1.0)];
        let p = Plot::new("trace", "t [s]", "x").add(Series::line("x", x));
        let one = dir.join(format!("friction_fmu_svg_{}_one.svg", std::process::id()));
        let many = one.with_file_name(format!("friction_fmu_svg_{}_many.svg", std::process::id()));
        p.write(&one).unwrap();
        write_panels(&[p], 2, &many).unwrap();
        for f in [one, many] {
            let text = std::fs::read_to_string(&f).unwrap();
            assert!(text.starts_with("<?xml") && text.trim_end().ends_with("</svg>"));
            let _ = std::fs::remove_file(f);
        }
    }
}
