//! One self-contained HTML report per result command (`--report DIR` writes `DIR/report.html`):
//! the figures as inline SVG, the tables with the paper's values beside ours, the command line
//! and version that made it, and a caption under each figure. No scripts, no external fonts or
//! styles, no network: the file opens from disk anywhere.
//!
//! Every number of a table is looked up in the serialised result ([`Doc::num`]) — the JSON
//! `--json` prints — and carries its JSON path (`data-src`, `data-json`) and exact value
//! (`data-value`), so a test can check the page against the JSON (tests/browser/).
//!
//! A result page opens with its verdict ([`Report::verdict`]): a few sentences in words and
//! numbers saying what the command found, before any figure or table, its numbers (and counts,
//! [`Doc::count`]) carrying their JSON paths as the tables' do. The figure that shows the
//! verdict ([`Report::key_figure`]) comes directly after it, then the rest of the page.

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
    /// The length of the array at `path` of the result (a count of cells, effects, steps).
    Count {
        /// Which JSON document.
        src: &'static str,
        /// Dot-separated path of the array.
        path: String,
        /// Its length.
        n: usize,
    },
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

    /// The length of the array at `path`, as a count cell (a path that is not an array counts
    /// 0, a programming error the browser test catches).
    pub fn count(&self, path: &str) -> Cell {
        Cell::Count {
            src: self.src,
            path: path.to_string(),
            n: lookup(self.json, path)
                .and_then(Value::as_array)
                .map_or(0, Vec::len),
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

/// Significant digits of `x`'s shortest round-trip form (`0.02` → 1, `180` → 2), so a value
/// given by the user (a swept value, the days of a run) is shown as written.
pub fn digits(x: f64) -> usize {
    let e = format!("{x:e}");
    let mantissa = e.split('e').next().unwrap_or("");
    mantissa.chars().filter(char::is_ascii_digit).count().max(1)
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
        Cell::Count { src, path, n } => format!(
            "<td class=\"num\" data-src=\"{src}\" data-json-len=\"{}\">{n}</td>",
            escape(path)
        ),
    }
}

/// A cell inside a verdict sentence: text as it is, a number or a count as a `span` carrying
/// its JSON path as a table cell does.
fn inline_html(c: &Cell) -> String {
    match c {
        Cell::Text(t) => escape(t),
        Cell::Json {
            src,
            path,
            value,
            sig,
        } => format!(
            "<span class=\"num\" data-src=\"{src}\" data-json=\"{}\" data-value=\"{value:?}\">{}</span>",
            escape(path),
            format_sig(*value, *sig)
        ),
        Cell::Paper(v, _) => format!("<span class=\"paper\" title=\"published value\">{v}</span>"),
        Cell::Count { src, path, n } => format!(
            "<span class=\"num\" data-src=\"{src}\" data-json-len=\"{}\">{n}</span>",
            escape(path)
        ),
    }
}

/// Words of a verdict sentence: `Cell::Text`.
pub fn words(t: impl Into<String>) -> Cell {
    Cell::Text(t.into())
}

/// A report page under construction.
pub struct Report {
    title: String,
    /// The verdict's sentences, written first whenever they were added.
    verdict: Vec<Vec<Cell>>,
    /// The figures that show the verdict, written right after it.
    key: String,
    body: String,
    figures: usize,
    paper_values: bool,
}

impl Report {
    /// An empty report titled `title`.
    pub fn new(title: &str) -> Self {
        Self {
            title: title.into(),
            verdict: Vec::new(),
            key: String::new(),
            body: String::new(),
            figures: 0,
            paper_values: false,
        }
    }

    /// A sentence of the page's verdict: its words and numbers in order. The verdict opens the
    /// page, before every other block, in the order the sentences were added.
    pub fn verdict(&mut self, sentence: Vec<Cell>) {
        self.verdict.push(sentence);
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
        let html = self.figure_html(path, caption)?;
        self.body.push_str(&html);
        Ok(())
    }

    /// A figure that shows the verdict: written directly after the verdict block, before every
    /// other block, in the order such figures were added. A missing file is an error naming it.
    pub fn key_figure(&mut self, path: &Path, caption: &str) -> Result<()> {
        let html = self.figure_html(path, caption)?;
        self.key.push_str(&html);
        Ok(())
    }

    /// The `figure` element of the SVG at `path` (counted in the footer).
    fn figure_html(&mut self, path: &Path, caption: &str) -> Result<String> {
        let svg = std::fs::read_to_string(path)
            .with_context(|| format!("report: cannot read the figure {}", path.display()))?;
        // The XML declaration is not allowed inside HTML.
        let start = svg.find("<svg").unwrap_or(0);
        let name = path
            .file_stem()
            .map_or(String::new(), |s| s.to_string_lossy().into_owned());
        self.figures += 1;
        Ok(format!(
            "<figure id=\"{n}\" data-figure=\"{n}\">{}<figcaption><b>{n}.svg</b> — {}</figcaption></figure>\n",
            &svg[start..],
            escape(caption),
            n = escape(&name)
        ))
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
             {verdict}{k}{b}<footer>rins {v} · {f} figures · self-contained: no scripts, fonts or network</footer>\n\
             </body></html>\n",
            t = escape(&self.title),
            c = escape(&command.join(" ")),
            v = env!("CARGO_PKG_VERSION"),
            verdict = self.verdict_html(),
            k = self.key,
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

impl Report {
    /// The verdict block (empty without sentences).
    fn verdict_html(&self) -> String {
        if self.verdict.is_empty() {
            return String::new();
        }
        let mut out = String::from("<section class=\"verdict\" id=\"verdict\"><h2>Verdict</h2>\n");
        for sentence in &self.verdict {
            let text: String = sentence.iter().map(inline_html).collect();
            let _ = writeln!(out, "<p>{text}</p>");
        }
        out.push_str("</section>\n");
        out
    }
}

/// The page's only style sheet (system fonts only).
const STYLE: &str = "body{font-family:system-ui,sans-serif;max-width:980px;margin:1em auto;\
padding:0 1em;color:#222}h1{font-size:1.5em}h2{font-size:1.2em;margin-top:1.6em;border-bottom:1px solid #ccc}\
table{border-collapse:collapse;margin:.8em 0;font-size:.9em}caption{text-align:left;font-weight:bold;\
padding:.3em 0}th,td{border:1px solid #ccc;padding:.2em .5em}td.num{text-align:right;\
font-variant-numeric:tabular-nums}td.paper{background:#fdf3d8}figure{margin:1em 0}\
figure svg{max-width:100%;height:auto;border:1px solid #eee}figcaption{font-size:.9em;color:#444}\
.meta,footer{font-size:.85em;color:#555}footer{margin-top:2em}\
.verdict{background:#eef5ee;border-left:4px solid #4a8a4a;padding:.2em 1em;margin:1em 0}\
.verdict h2{margin-top:.4em;border:none}.verdict p{margin:.4em 0}";

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

    /// Issue 44: the verdict is the first block after the title and the command line, however
    /// late it was added, and its numbers and counts carry their JSON paths.
    #[test]
    fn the_verdict_opens_the_page_with_its_numbers_and_counts() {
        let json = serde_json::json!({"x": 0.0123456, "cells": [1, 2, 3]});
        let d = Doc {
            src: "t",
            json: &json,
        };
        let mut r = Report::new("T");
        r.table("table", &["a"], vec![vec![d.num("x", 3)]]);
        r.verdict(vec![
            words("x is "),
            d.num("x", 3),
            words(", "),
            d.count("cells"),
        ]);
        let dir = std::env::temp_dir().join(format!("rins-verdict-{}", std::process::id()));
        let page = std::fs::read_to_string(r.write(&dir).unwrap()).unwrap();
        let _ = std::fs::remove_dir_all(&dir);
        let after_meta = &page[page.find("</p>\n").unwrap() + 5..];
        assert!(
            after_meta.starts_with(
                "<section class=\"verdict\" id=\"verdict\"><h2>Verdict</h2>\n<p>x is <span \
                 class=\"num\" data-src=\"t\" data-json=\"x\" data-value=\"0.0123456\">0.0123</span>, \
                 <span class=\"num\" data-src=\"t\" data-json-len=\"cells\">3</span></p>\n</section>\n<table>"
            ),
            "{after_meta}"
        );
    }

    /// Issue 44: the figure that shows the verdict comes directly after it, before the tables
    /// and the other figures, however late it was added.
    #[test]
    fn the_key_figure_follows_the_verdict() {
        let dir = std::env::temp_dir().join(format!("rins-key-figure-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let svg = |stem: &str| {
            let f = dir.join(format!("{stem}.svg"));
            std::fs::write(
                &f,
                format!("<?xml version=\"1.0\"?><svg id=\"{stem}\"></svg>"),
            )
            .unwrap();
            f
        };
        let (other, key) = (svg("other"), svg("key"));
        let mut r = Report::new("T");
        r.table("table", &["a"], vec![vec![words("x")]]);
        r.figure(&other, "other").unwrap();
        r.verdict(vec![words("v")]);
        r.key_figure(&key, "shows v").unwrap();
        let page = std::fs::read_to_string(r.write(&dir).unwrap()).unwrap();
        let _ = std::fs::remove_dir_all(&dir);
        let after = &page[page.find("</section>\n").unwrap() + 11..];
        assert!(
            after.starts_with(
                "<figure id=\"key\" data-figure=\"key\"><svg id=\"key\"></svg><figcaption>\
                 <b>key.svg</b> — shows v</figcaption></figure>\n<table>"
            ),
            "{after}"
        );
        assert!(page.contains("· 2 figures ·"), "{page}");
    }
}
