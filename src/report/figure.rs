//! Figures as data: each figure is `<stem>.csv` (its points, after a header line) with
//! `<stem>.json` beside it (title, panels, axis labels with units, legend texts), drawn into
//! `<stem>.png` and `<stem>.svg` by the Python package (`python -m friction_fmu.figures DIR`,
//! python/friction_fmu/figures.py), which styles every solver and law alike in every figure.
//!
//! The CSV's columns: `panel,series,x,y` for line plots, `panel,x,y,value` for heat maps;
//! `panel` indexes the JSON's `panels`. Numbers are written so they read back to the same bits;
//! a value that is not finite is written `nan` (a gap in a line, a failed cell in a heat map).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// One line of a line plot. The name picks the style: a solver or law name (`dopri5`,
/// `trigonometric`) draws in that one's colour and marker in every figure.
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
}

/// What one panel shows.
pub enum Data {
    Lines(Vec<Series>),
    /// A heat map over a grid drawn as equal cells in the order given: `values[j][i]` at
    /// `(x[i], y[j])`, NaN where the point failed.
    Cells {
        x: Vec<f64>,
        y: Vec<f64>,
        values: Vec<Vec<f64>>,
    },
}

pub struct Panel {
    /// Without a letter: the drawing letters the panels (a), (b), ... in order.
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub log_x: bool,
    pub log_y: bool,
    pub data: Data,
}

pub struct Figure {
    pub title: String,
    /// Panels per row.
    pub columns: usize,
    /// A marker on every point of every line (else lines alone).
    pub markers: bool,
    /// Legend text of a series where it differs from its name.
    pub labels: Vec<(String, String)>,
    /// The colour bar's label (heat maps).
    pub value_label: String,
    pub panels: Vec<Panel>,
}

impl Series {
    pub fn new(name: &str, points: Vec<(f64, f64)>) -> Self {
        Series {
            name: name.to_string(),
            points,
        }
    }
}

impl Panel {
    /// A panel of lines on linear axes.
    pub fn lines(title: &str, x_label: &str, y_label: &str, series: Vec<Series>) -> Self {
        Panel {
            title: title.to_string(),
            x_label: x_label.to_string(),
            y_label: y_label.to_string(),
            log_x: false,
            log_y: false,
            data: Data::Lines(series),
        }
    }

    /// A heat map panel: `values[j][i]` at `(x[i], y[j])`.
    pub fn cells(
        title: &str,
        x_label: &str,
        y_label: &str,
        (x, y): (Vec<f64>, Vec<f64>),
        values: Vec<Vec<f64>>,
    ) -> Self {
        Panel {
            data: Data::Cells { x, y, values },
            ..Panel::lines(title, x_label, y_label, Vec::new())
        }
    }

    pub fn log_log(self) -> Self {
        Panel {
            log_x: true,
            log_y: true,
            ..self
        }
    }
}

impl Figure {
    pub fn new(title: &str, columns: usize, panels: Vec<Panel>) -> Self {
        Figure {
            title: title.to_string(),
            columns,
            markers: false,
            labels: Vec::new(),
            value_label: String::new(),
            panels,
        }
    }

    pub fn with_markers(self) -> Self {
        Figure {
            markers: true,
            ..self
        }
    }

    pub fn label(mut self, series: &str, text: &str) -> Self {
        self.labels.push((series.to_string(), text.to_string()));
        self
    }

    pub fn value_label(self, text: &str) -> Self {
        Figure {
            value_label: text.to_string(),
            ..self
        }
    }

    /// "lines" or "heatmap"; a figure does not mix them.
    fn kind(&self) -> Result<&'static str, String> {
        let cells = self.panels.iter();
        let cells = cells.filter(|p| matches!(p.data, Data::Cells { .. }));
        match cells.count() {
            0 => Ok("lines"),
            n if n == self.panels.len() => Ok("heatmap"),
            _ => Err(format!(
                "figure \"{}\": expected only line panels or only heat map panels",
                self.title
            )),
        }
    }

    /// The CSV: a header line, then one row per point.
    pub fn csv(&self) -> Result<String, String> {
        let mut out = String::new();
        if self.kind()? == "lines" {
            out.push_str("panel,series,x,y\n");
        } else {
            out.push_str("panel,x,y,value\n");
        }
        for (index, panel) in self.panels.iter().enumerate() {
            match &panel.data {
                Data::Lines(series) => {
                    for s in series {
                        let name = csv_field(&s.name);
                        for &(x, y) in &s.points {
                            let _ = writeln!(out, "{index},{name},{},{}", number(x), number(y));
                        }
                    }
                }
                Data::Cells { x, y, values } => {
                    for (j, &yv) in y.iter().enumerate() {
                        for (i, &xv) in x.iter().enumerate() {
                            let v = values.get(j).and_then(|row| row.get(i)).copied();
                            let v = number(v.unwrap_or(f64::NAN));
                            let _ = writeln!(out, "{index},{},{},{v}", number(xv), number(yv));
                        }
                    }
                }
            }
        }
        Ok(out)
    }

    /// The JSON description (friction_fmu.figures reads it).
    pub fn json(&self) -> Result<String, String> {
        let mut out = String::from("{\n");
        let _ = writeln!(out, "  \"kind\": {},", json_string(self.kind()?));
        let _ = writeln!(out, "  \"title\": {},", json_string(&self.title));
        let _ = writeln!(out, "  \"columns\": {},", self.columns.max(1));
        let _ = writeln!(out, "  \"markers\": {},", self.markers);
        let _ = writeln!(out, "  \"value\": {},", json_string(&self.value_label));
        let labels: Vec<String> = self
            .labels
            .iter()
            .map(|(k, v)| format!("{}: {}", json_string(k), json_string(v)))
            .collect();
        let _ = writeln!(out, "  \"labels\": {{{}}},", labels.join(", "));
        out.push_str("  \"panels\": [\n");
        for (i, p) in self.panels.iter().enumerate() {
            let _ = write!(
                out,
                "    {{\"title\": {}, \"x\": {}, \"y\": {}, \"log_x\": {}, \"log_y\": {}}}",
                json_string(&p.title),
                json_string(&p.x_label),
                json_string(&p.y_label),
                p.log_x,
                p.log_y
            );
            out.push_str(if i + 1 < self.panels.len() {
                ",\n"
            } else {
                "\n"
            });
        }
        out.push_str("  ]\n}\n");
        Ok(out)
    }

    /// Writes `<dir>/<stem>.csv` and `<dir>/<stem>.json`; returns the CSV's path. A file that
    /// already holds the same text is left untouched, so its drawing stays up to date (the
    /// drawing redraws what is newer than its PNG and SVG).
    pub fn write(&self, dir: &Path, stem: &str) -> Result<PathBuf, String> {
        let (csv, json) = (self.csv()?, self.json()?);
        std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        let path = dir.join(format!("{stem}.csv"));
        write_if_changed(&path, &csv)?;
        write_if_changed(&path.with_extension("json"), &json)?;
        Ok(path)
    }
}

fn write_if_changed(path: &Path, text: &str) -> Result<(), String> {
    if std::fs::read(path).is_ok_and(|old| old == text.as_bytes()) {
        return Ok(());
    }
    std::fs::write(path, text).map_err(|e| format!("{}: {e}", path.display()))
}

/// The shortest text that reads back to the same f64: plain digits where they are short,
/// else the exponent form (1e-10, not 0.0000000001); `nan` for anything not finite.
fn number(v: f64) -> String {
    if !v.is_finite() {
        return "nan".into();
    }
    let (plain, exp) = (format!("{v}"), format!("{v:e}"));
    if plain.len() <= exp.len() {
        plain
    } else {
        exp
    }
}

fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

fn json_string(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            c if (c as u32) < 0x20 => {
                let _ = write!(out, "\\u{:04x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// The interpreter of the project's Python environment (the README's install line makes it).
#[cfg(windows)]
const VENV_PYTHON: &str = ".venv\\Scripts\\python.exe";
#[cfg(not(windows))]
const VENV_PYTHON: &str = ".venv/bin/python";

/// Draws every figure in `dir` into PNG and SVG with `.venv`'s Python, when it has matplotlib;
/// else prints one line: where the data is and the command that draws it. The package is taken
/// from this source tree, so the figures are drawn by the code they were written for. Err when
/// the drawing itself fails.
pub fn draw(dir: &Path) -> Result<(), String> {
    let shown = dir.display();
    let command = format!("{VENV_PYTHON} -m friction_fmu.figures {shown}");
    let python = Path::new(VENV_PYTHON);
    let install = ".venv/bin/pip install -e 'python[dask]'";
    if !python.is_file() {
        println!(
            "figure data (CSV) in {shown}; to draw it as PNG and SVG: python3 -m venv .venv && {install} && {command}"
        );
        return Ok(());
    }
    let source = Path::new(env!("CARGO_MANIFEST_DIR")).join("python");
    let old = std::env::var_os("PYTHONPATH").unwrap_or_default();
    // An empty entry would put the working directory on the path.
    let old = std::env::split_paths(&old).filter(|p| !p.as_os_str().is_empty());
    let path = std::env::join_paths(std::iter::once(source).chain(old))
        .map_err(|e| format!("PYTHONPATH: {e}"))?;
    // find_spec does not import: the check costs an interpreter start, not matplotlib's import.
    let check = "import importlib.util as u, sys; \
                 sys.exit(0 if u.find_spec('matplotlib') and u.find_spec('friction_fmu') else 3)";
    let ready = std::process::Command::new(python)
        .args(["-c", check])
        .env("PYTHONPATH", &path)
        .status()
        .is_ok_and(|s| s.success());
    if !ready {
        println!("figure data (CSV) in {shown}; to draw it as PNG and SVG: {install} && {command}");
        return Ok(());
    }
    let status = std::process::Command::new(python)
        .args(["-m", "friction_fmu.figures"])
        .arg(dir)
        .env("PYTHONPATH", &path)
        .status()
        .map_err(|e| format!("{VENV_PYTHON}: {e}"))?;
    if status.success() {
        Ok(())
    } else {
        Err(format!(
            "drawing the figures failed ({status}); the data is in {shown}, drawn by {command}"
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn two_solvers() -> Figure {
        let dopri5 = Series::new("dopri5", vec![(1e-4, 2.5e-3), (2e-4, f64::NAN)]);
        let rk4 = Series::new("rk4", vec![(0.5, 1e-10)]);
        let quoted = Series::new("a, \"b\"", vec![(3.0, -0.0)]);
        Figure::new(
            "work, precision",
            2,
            vec![
                Panel::lines("one", "t (s)", "e", vec![dopri5, rk4]).log_log(),
                Panel::lines("two", "u (m)", "v \"m/s\"", vec![quoted]),
            ],
        )
        .with_markers()
        .label("rk4", "rk4, 50 steps")
    }

    #[test]
    fn csv_has_the_header_and_one_row_per_point() {
        let csv = two_solvers().csv().unwrap();
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(
            lines,
            [
                "panel,series,x,y",
                "0,dopri5,1e-4,0.0025",
                "0,dopri5,2e-4,nan",
                "0,rk4,0.5,1e-10",
                "1,\"a, \"\"b\"\"\",3,-0",
            ]
        );
    }

    #[test]
    fn numbers_read_back_to_the_same_bits() {
        for v in [
            1.085595261984e-2,
            1e300,
            -3.634e-7,
            0.1 + 0.2,
            5e-324,
            123456789.0,
        ] {
            let text = number(v);
            assert_eq!(
                text.parse::<f64>().unwrap().to_bits(),
                v.to_bits(),
                "{text}"
            );
        }
        assert_eq!(number(1e-10), "1e-10");
        assert_eq!(number(f64::INFINITY), "nan");
    }

    #[test]
    fn heat_map_rows_run_over_x_then_y() {
        let grid = (vec![0.3, 0.6], vec![0.1, 0.5]);
        let values = vec![vec![1.0, 2.0], vec![f64::NAN, 4.0]];
        let panel = Panel::cells("3 kHz", "va (mm/s)", "vd (mm/s)", grid, values);
        let figure = Figure::new("Fig. 8", 2, vec![panel]).value_label("FFx_mean / FC");
        assert_eq!(
            figure.csv().unwrap(),
            "panel,x,y,value\n0,0.3,0.1,1\n0,0.6,0.1,2\n0,0.3,0.5,nan\n0,0.6,0.5,4\n"
        );
        assert!(figure
            .json()
            .unwrap()
            .contains("\"kind\": \"heatmap\",\n  \"title\": \"Fig. 8\""));
    }

    #[test]
    fn json_is_escaped_and_describes_every_panel() {
        let json = two_solvers().json().unwrap();
        assert!(json.contains("\"kind\": \"lines\""));
        assert!(json.contains("\"markers\": true"));
        assert!(json.contains("\"labels\": {\"rk4\": \"rk4, 50 steps\"}"));
        assert!(json.contains(
            "{\"title\": \"one\", \"x\": \"t (s)\", \"y\": \"e\", \"log_x\": true, \"log_y\": true},\n"
        ));
        assert!(json.contains("\"y\": \"v \\\"m/s\\\"\""));
        assert_eq!(json.matches("\"title\"").count(), 3);
    }

    #[test]
    fn mixed_panels_are_refused_and_files_are_written() {
        let mut figure = two_solvers();
        let cells = Data::Cells {
            x: vec![],
            y: vec![],
            values: vec![],
        };
        let dir = std::env::temp_dir().join(format!("friction_fmu_figure_{}", std::process::id()));
        let path = two_solvers().write(&dir, "wp").unwrap();
        assert_eq!(path, dir.join("wp.csv"));
        let csv = std::fs::read_to_string(&path).unwrap();
        assert!(csv.starts_with("panel,series,x,y\n"));
        assert!(std::fs::read_to_string(dir.join("wp.json"))
            .unwrap()
            .starts_with("{\n  \"kind\": \"lines\""));
        // written again unchanged: left untouched (its drawing stays up to date)
        let modified = |p: &Path| std::fs::metadata(p).and_then(|m| m.modified()).unwrap();
        let before = modified(&path);
        std::thread::sleep(std::time::Duration::from_millis(20));
        two_solvers().write(&dir, "wp").unwrap();
        assert_eq!(modified(&path), before);
        let _ = std::fs::remove_dir_all(&dir);
        figure.panels[1].data = cells;
        assert!(figure.csv().unwrap_err().contains("only line panels"));
    }
}
