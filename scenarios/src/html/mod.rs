//! One self-contained HTML report per result command (`--report DIR` writes `DIR/report.html`):
//! the figures as inline SVG, the tables with the paper's values beside ours, the command line
//! and version that made it, and a caption under each figure. No scripts, no external fonts or
//! styles, no network: the file opens from disk anywhere.
//!
//! Every number of a table is looked up in the serialised result ([`Doc::num`]) — the JSON
//! `--json` prints — and carries its JSON path (`data-src`, `data-json`) and exact value
//! (`data-value`), so a test can check the page against the JSON (tests/browser/).

pub mod results;
pub mod sweep;

use std::fmt::Write;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use serde_json::Value;

/// Escapes text for HTML element content and attribute values.
pub fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// A table cell.
pub enum Cell {
    /// Text.
    Text(String),
    /// A number of the result: its JSON source and path, its value, decimals shown.
    Json {
        /// Which JSON document (`table4`, `calibration`, …).
        src: &'static str,
        /// Dot-separated path in it (`uncompensated.abs_lat_nm.median`, `runs.0.chamber_c`).
        path: String,
        /// The value at that path.
        value: f64,
        /// Significant figures shown.
        sig: usize,
    },
    /// A published value of the paper (not in our JSON).
    Paper(f64, usize),
}

/// A serialised result and the name the page gives it.
pub struct Doc<'a> {
    /// Source name (`data-src` of its cells).
    pub src: &'static str,
    /// The JSON `--json` prints for it.
    pub json: &'a Value,
}

impl Doc<'_> {
    /// The number at `path` (dot-separated keys and indices) as a cell with `sig` significant
    /// figures; a path that is missing or not a number reads "n/a" (a programming error the
    /// browser test catches).
    pub fn num(&self, path: &str, sig: usize) -> Cell {
        match lookup(self.json, path).and_then(Value::as_f64) {
            Some(value) => Cell::Json {
                src: self.src,
                path: path.to_string(),
                value,
                sig,
            },
            None => Cell::Text("n/a".into()),
        }
    }

    /// The string at `path`, as text.
    pub fn text(&self, path: &str) -> Cell {
        Cell::Text(
            lookup(self.json, path)
                .map(|v| v.as_str().map_or_else(|| v.to_string(), str::to_string))
                .unwrap_or_else(|| "n/a".into()),
        )
    }
}

/// The value at a dot-separated path of keys and array indices.
pub fn lookup<'v>(v: &'v Value, path: &str) -> Option<&'v Value> {
    path.split('.').try_fold(v, |v, k| match v {
        Value::Array(a) => a.get(k.parse::<usize>().ok()?),
        Value::Object(o) => o.get(k),
        _ => None,
    })
}

/// `v` with `sig` significant figures (fixed notation between 1e-4 and 1e6).
pub fn format_sig(v: f64, sig: usize) -> String {
    if !v.is_finite() {
        return v.to_string();
    }
    if v == 0.0 {
        return "0".into();
    }
    let mag = v.abs().log10().floor() as i32;
    if !(-4..6).contains(&mag) {
        return format!("{:.*e}", sig.saturating_sub(1), v);
    }
    let decimals = (sig as i32 - 1 - mag).max(0) as usize;
    format!("{v:.decimals$}")
}

fn cell_html(c: &Cell) -> String {
    match c {
        Cell::Text(t) => format!("<td>{}</td>", escape(t)),
        Cell::Json {
            src,
            path,
            value,
            sig,
        } => format!(
            "<td class=\"num\" data-src=\"{src}\" data-json=\"{}\" data-value=\"{value:?}\">{}</td>",
            escape(path),
            format_sig(*value, *sig)
        ),
        // As printed in the paper (its own digits).
        Cell::Paper(v, _) => format!("<td class=\"num paper\" title=\"published value\">{v}</td>"),
    }
}

/// A report page under construction.
pub struct Report {
    title: String,
    body: String,
    figures: usize,
    paper_values: bool,
}

impl Report {
    /// An empty report titled `title`.
    pub fn new(title: &str) -> Self {
        Self {
            title: title.into(),
            body: String::new(),
            figures: 0,
            paper_values: false,
        }
    }

    /// A heading and a paragraph (either may be empty).
    pub fn text(&mut self, heading: &str, paragraph: &str) {
        if !heading.is_empty() {
            let _ = writeln!(self.body, "<h2>{}</h2>", escape(heading));
        }
        if !paragraph.is_empty() {
            let _ = writeln!(self.body, "<p>{}</p>", escape(paragraph));
        }
    }

    /// A table: caption, column headings and rows. Columns of the paper's values are shaded.
    pub fn table(&mut self, caption: &str, columns: &[&str], rows: Vec<Vec<Cell>>) {
        let _ = writeln!(
            self.body,
            "<table><caption>{}</caption><thead><tr>{}</tr></thead><tbody>",
            escape(caption),
            columns
                .iter()
                .map(|c| format!("<th>{}</th>", escape(c)))
                .collect::<String>()
        );
        self.paper_values |= rows.iter().flatten().any(|c| matches!(c, Cell::Paper(..)));
        for r in rows {
            let _ = writeln!(
                self.body,
                "<tr>{}</tr>",
                r.iter().map(cell_html).collect::<String>()
            );
        }
        self.body.push_str("</tbody></table>\n");
    }

    /// The SVG at `path`, inline, with `caption` under it. A missing file is an error naming it.
    pub fn figure(&mut self, path: &Path, caption: &str) -> Result<()> {
        let svg = std::fs::read_to_string(path)
            .with_context(|| format!("report: cannot read the figure {}", path.display()))?;
        // The XML declaration is not allowed inside HTML.
        let start = svg.find("<svg").unwrap_or(0);
        let name = path
            .file_stem()
            .map_or(String::new(), |s| s.to_string_lossy().into_owned());
        self.figures += 1;
        let _ = writeln!(
            self.body,
            "<figure id=\"{n}\" data-figure=\"{n}\">{}<figcaption><b>{n}.svg</b> — {}</figcaption></figure>",
            &svg[start..],
            escape(caption),
            n = escape(&name)
        );
        Ok(())
    }

    /// Writes `dir/report.html` and returns its path. The footer names the command line and
    /// the version that made it.
    pub fn write(&self, dir: &Path) -> Result<PathBuf> {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
        let command: Vec<String> = std::env::args().collect();
        let page = format!(
            "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
             <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\
             <title>{t}</title><style>{STYLE}</style></head><body>\n<h1>{t}</h1>\n\
             <p class=\"meta\">Made by <code id=\"command\">{c}</code> with rins {v}.{p}</p>\n\
             {b}<footer>rins {v} · {f} figures · self-contained: no scripts, fonts or network</footer>\n\
             </body></html>\n",
            t = escape(&self.title),
            c = escape(&command.join(" ")),
            v = env!("CARGO_PKG_VERSION"),
            b = self.body,
            f = self.figures,
            p = if self.paper_values {
                " Shaded cells are the paper's published values (Seo et al., Sensors 2022, 22, 8355)."
            } else {
                ""
            },
        );
        let path = dir.join("report.html");
        std::fs::write(&path, page).with_context(|| format!("cannot write {}", path.display()))?;
        Ok(path)
    }
}

/// The page's only style sheet (system fonts only).
const STYLE: &str = "body{font-family:system-ui,sans-serif;max-width:980px;margin:1em auto;\
padding:0 1em;color:#222}h1{font-size:1.5em}h2{font-size:1.2em;margin-top:1.6em;border-bottom:1px solid #ccc}\
table{border-collapse:collapse;margin:.8em 0;font-size:.9em}caption{text-align:left;font-weight:bold;\
padding:.3em 0}th,td{border:1px solid #ccc;padding:.2em .5em}td.num{text-align:right;\
font-variant-numeric:tabular-nums}td.paper{background:#fdf3d8}figure{margin:1em 0}\
figure svg{max-width:100%;height:auto;border:1px solid #eee}figcaption{font-size:.9em;color:#444}\
.meta,footer{font-size:.85em;color:#555}footer{margin-top:2em}";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_keep_their_path_and_exact_value() {
        let json = serde_json::json!({"a": {"b": [1.5, -0.000123456789]}});
        let d = Doc {
            src: "t",
            json: &json,
        };
        let c = cell_html(&d.num("a.b.1", 4));
        assert_eq!(
            c,
            "<td class=\"num\" data-src=\"t\" data-json=\"a.b.1\" data-value=\"-0.000123456789\">-0.0001235</td>"
        );
        assert_eq!(cell_html(&d.num("a.c", 3)), "<td>n/a</td>");
        assert_eq!(format_sig(2.7088, 5), "2.7088");
        assert_eq!(format_sig(1234567.0, 3), "1.23e6");
        assert_eq!(escape("<a & \"b\">"), "&lt;a &amp; &quot;b&quot;&gt;");
    }
}
