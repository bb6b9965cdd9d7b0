//! The figure rules (`figures::rules`) on real results, checked on the geometry the plotting
//! code placed and on the SVG text it wrote (not by eye): `bias_by_position` has a categorical
//! position axis and no legend box covers a plotted mark; the week-long paper figures shrink at
//! least 5× as envelopes, and each envelope's extremes are the series' extremes; Figure 2 has a
//! difference panel (uncompensated − compensated per axis); print size: every text of
//! `bias_by_position`, `residual_vs_temperature`, Figures 2-3 and `sea_end_error` has a font
//! size of at least `rules::min_text_px` of the figure's width (8 pt when printed 3.5 in, one
//! journal column, wide); headroom: the data range of every panel, error-bar ends included,
//! computed here from the data, lies `HEADROOM_PX` inside the padded axis range the panel was
//! drawn with, and every drawn mark keeps `HEADROOM_PX` from the frame; units are typeset
//! ("µg", "°C") and the PNG font has their glyphs.

use std::path::{Path, PathBuf};

use rins_report::figures::paper::paired_figures;
use rins_report::figures::plot::{BAR_DOT_PX, Kind, Panel, PanelGeometry};
use rins_report::figures::rules::{
    HEADROOM_PX, MIN_TEXT_PT, Rect, SCATTER_X_PAD_FRAC, min_text_px, text_pt,
};
use rins_scenarios::commands::measure::{MeasureArgs, run as measure};

/// The SVG's pixel width (its `width` attribute) and every `font-size` of its text, px, with
/// the text.
fn font_sizes_px(svg: &str) -> (u32, Vec<(f64, String)>) {
    let num = |t: &str, name: &str| -> Option<f64> {
        let i = t.find(&format!(" {name}=\""))? + name.len() + 3;
        t[i..i + t[i..].find('"')?].parse::<f64>().ok()
    };
    let width = num(svg, "width").expect("svg width") as u32;
    let sizes = svg
        .split("<text")
        .skip(1)
        .filter_map(|t| {
            let head = &t[..t.find('>')?];
            let body = &t[t.find('>')? + 1..];
            let text = body[..body.find("</text>")?].trim().to_string();
            Some((num(head, "font-size")?, text))
        })
        .collect();
    (width, sizes)
}

/// Every `font-size` of an SVG's text, in pt when the figure is printed at
/// `rules::PRINT_WIDTH_IN`, with the text.
fn text_sizes_pt(svg: &str) -> Vec<(f64, String)> {
    let (width, sizes) = font_sizes_px(svg);
    sizes
        .into_iter()
        .map(|(px, t)| (text_pt(px, width), t))
        .collect()
}

/// No text of `svg` (figure `name`) has a font size below the minimum for the figure's pixel
/// width (`min_text_px`: 8 pt at one column width); some text is there to check.
fn text_at_least_8_pt(name: &str, svg: &str) {
    let (width, sizes) = font_sizes_px(svg);
    assert!(sizes.len() > 5, "{name}: {} texts", sizes.len());
    let min = min_text_px(width);
    // The reference by hand for the usual width: 8/72 in at 900 px / 3.5 in.
    if width == 900 {
        assert!((min - 28.571).abs() < 1e-3, "{min}");
    }
    for (px, text) in sizes {
        assert!(
            px >= min - 1e-6,
            "{name}: \"{text}\" is {px:.2} px ({:.2} pt at 3.5 in wide), below {min:.2} px ({MIN_TEXT_PT} pt) for {width} px",
            text_pt(px, width)
        );
    }
}

/// Every panel's marks, with their reach (dot radius, half stroke), lie `HEADROOM_PX` inside
/// the plot frame vertically, and horizontally too when `x_also` (scatter and bar panels).
fn marks_keep_headroom(name: &str, g: &[PanelGeometry], x_also: bool) {
    for (k, p) in g.iter().enumerate() {
        let e: Rect = p.extent.expect("marks");
        let h = HEADROOM_PX - 1; // rounding of the pixel mapping
        assert!(
            e.y0 >= p.plot.y0 + h && e.y1 <= p.plot.y1 - h,
            "{name} panel {k}: marks {e:?} within {HEADROOM_PX} px of the frame {:?} (top/bottom)",
            p.plot
        );
        if x_also {
            assert!(
                e.x0 >= p.plot.x0 + h && e.x1 <= p.plot.x1 - h,
                "{name} panel {k}: marks {e:?} within {HEADROOM_PX} px of the frame {:?} (left/right)",
                p.plot
            );
        }
    }
}

/// The x and y range of a panel's data: every finite point of every line, so the ends of an
/// error bar or interval, not only its estimate.
fn data_range(p: &Panel) -> ((f64, f64), (f64, f64)) {
    let mut r = ((f64::MAX, f64::MIN), (f64::MAX, f64::MIN));
    for &(x, y) in p.lines.iter().flat_map(|l| &l.points) {
        if x.is_finite() && y.is_finite() {
            r = ((r.0.0.min(x), r.0.1.max(x)), (r.1.0.min(y), r.1.1.max(y)));
        }
    }
    r
}

/// Headroom in data terms: each panel's data y range (`data[k].1`) lies inside the y axis
/// range it was drawn with, each end at least `HEADROOM_PX` px (less one of rounding) inside
/// at the panel's plot height; with `x_px` the x range too, each end at least that many px
/// inside at the plot width. Returns the smallest margins found, px (y, x).
fn data_inside_padded_axes(
    name: &str,
    data: &[((f64, f64), (f64, f64))],
    g: &[PanelGeometry],
    x_px: Option<f64>,
) -> (f64, f64) {
    assert_eq!(data.len(), g.len(), "{name}: one data range per panel");
    let (mut min_y, mut min_x) = (f64::MAX, f64::MAX);
    for (k, (d, p)) in data.iter().zip(g).enumerate() {
        let ((ax0, ax1), (ay0, ay1)) = p.axes;
        let (w, h) = (
            (p.plot.x1 - p.plot.x0) as f64,
            (p.plot.y1 - p.plot.y0) as f64,
        );
        let below = (d.1.0 - ay0) / (ay1 - ay0) * h;
        let above = (ay1 - d.1.1) / (ay1 - ay0) * h;
        assert!(
            below >= (HEADROOM_PX - 1) as f64 && above >= (HEADROOM_PX - 1) as f64,
            "{name} panel {k}: data y {:?} in the axis {:?}: {below:.1} px below, {above:.1} px above (at least {HEADROOM_PX})",
            d.1,
            (ay0, ay1)
        );
        min_y = min_y.min(below).min(above);
        if let Some(need) = x_px {
            let left = (d.0.0 - ax0) / (ax1 - ax0) * w;
            let right = (ax1 - d.0.1) / (ax1 - ax0) * w;
            assert!(
                left >= need - 1.0 && right >= need - 1.0,
                "{name} panel {k}: data x {:?} in the axis {:?}: {left:.1} px left, {right:.1} px right (at least {need:.1})",
                d.0,
                (ax0, ax1)
            );
            min_x = min_x.min(left).min(right);
        }
    }
    (min_y, min_x)
}

fn docs(p: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../docs/examples")
        .join(p)
}

/// Every mark of every panel is outside that panel's legend box.
fn no_mark_under_legend(g: &[PanelGeometry]) {
    for (k, p) in g.iter().enumerate() {
        let Some(l) = p.legend else { continue };
        assert!(!p.marks.is_empty(), "panel {k} has no marks");
        for &(a, b) in &p.marks {
            assert!(
                !l.touches_segment(a, b),
                "panel {k}: legend {l:?} covers the mark {a:?}-{b:?}"
            );
        }
    }
}

#[test]
fn bias_by_position_is_categorical_and_its_legends_cover_no_point() {
    let dir = std::env::temp_dir().join(format!("rins-figrules-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let data = dir.join("unit.csv");
    measure(&MeasureArgs {
        scenario: docs("diagnosis-truth.toml"),
        out: data.clone(),
        format: "csv".into(),
        overrides: Default::default(),
    })
    .unwrap();
    let model = rins_scenario::Scenario::load(&docs("diagnosis-model.toml")).unwrap();
    let m = rins_mvm::reader::read(&data).unwrap();
    let h = rins_mvm::to_history(m, "unit").unwrap();
    let opts = rins_mvm::Options {
        diagnose: true,
        ..Default::default()
    };
    let an = rins_mvm::analyse(&model.plant, &h, &opts);
    assert!(an.after().is_some(), "the hidden effect is fitted");
    let (svg, g) = rins_scenarios::diagnose::render_bias_by_position(&an).unwrap();
    // The report's other figure drawn from the same analysis, as written.
    rins_scenarios::diagnose::write_report(&dir, &an).unwrap();
    let rvt = std::fs::read_to_string(dir.join("residual_vs_temperature.svg")).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(g.len(), 6, "one panel per channel");
    // Print size, headroom for every bar (the accel_y/z bars touched the top frame), units.
    text_at_least_8_pt("bias_by_position", &svg);
    text_at_least_8_pt("residual_vs_temperature", &rvt);
    marks_keep_headroom("bias_by_position", &g, true);
    // The bars' ends computed here from the cells, as the figure's caption defines them: per
    // channel and position the inverse-variance mean residual ± 1.96 / sqrt(Σ 1/σ²), before at
    // x = k - 0.15 and after the fitted effects at k + 0.15.
    let ranges: Vec<_> = rins_mvm::CHANNELS
        .iter()
        .map(|ch| {
            let mut r = ((f64::MAX, f64::MIN), (f64::MAX, f64::MIN));
            for (report, shift) in [(&an.comparison, -0.15), (an.after().unwrap(), 0.15)] {
                for (k, pos) in rins_scenarios::diagnose::POSITIONS.iter().enumerate() {
                    let cells: Vec<_> = report
                        .cells
                        .iter()
                        .filter(|c| c.channel == *ch && c.position == *pos)
                        .collect();
                    if cells.is_empty() {
                        continue;
                    }
                    let w: f64 = cells.iter().map(|c| c.noise_floor.powi(-2)).sum();
                    let m: f64 = cells
                        .iter()
                        .map(|c| c.residual * c.noise_floor.powi(-2))
                        .sum::<f64>()
                        / w;
                    let e = 1.96 / w.sqrt();
                    let x = k as f64 + shift;
                    r = (
                        (r.0.0.min(x), r.0.1.max(x)),
                        (r.1.0.min(m - e), r.1.1.max(m + e)),
                    );
                }
            }
            r
        })
        .collect();
    let (margin, _) =
        data_inside_padded_axes("bias_by_position", &ranges, &g, Some(HEADROOM_PX as f64));
    eprintln!("bias_by_position: smallest margin of a bar end to the frame {margin:.1} px");
    for (name, svg) in [
        ("bias_by_position", &svg),
        ("residual_vs_temperature", &rvt),
    ] {
        let texts: Vec<String> = text_sizes_pt(svg).into_iter().map(|t| t.1).collect();
        assert!(
            texts.iter().any(|t| t.contains("(µg)")),
            "{name}: accelerometer axes in µg"
        );
        assert!(
            !texts
                .iter()
                .any(|t| t.contains("(ug)") || t.contains("deg C") || t.contains("(deg/h)")),
            "{name}: an untypeset unit in {texts:?}"
        );
    }
    assert!(rvt.contains("sensor temperature (°C)"), "°C on the x axis");
    for (k, p) in g.iter().enumerate() {
        // Categorical: the four positions at increasing pixel x, inside the plot, in order.
        let names: Vec<&str> = p.categories.iter().map(|c| c.0.as_str()).collect();
        assert_eq!(names, rins_scenarios::diagnose::POSITIONS, "panel {k}");
        let xs: Vec<i32> = p.categories.iter().map(|c| c.1).collect();
        assert!(xs.windows(2).all(|w| w[0] < w[1]), "panel {k}: {xs:?}");
        assert!(xs[0] > p.plot.x0 && xs[3] < p.plot.x1, "panel {k}: {xs:?}");
        // Every bar sits within a quarter slot of its category's label.
        let slot = (xs[1] - xs[0]) as f64;
        for &(a, b) in &p.marks {
            if a.0 == b.0 {
                let near = xs.iter().map(|x| (x - a.0).abs()).min().unwrap() as f64;
                assert!(
                    near <= 0.25 * slot,
                    "panel {k}: bar at x {} off {xs:?}",
                    a.0
                );
            }
        }
        assert!(p.legend.is_some(), "panel {k} has a legend");
    }
    no_mark_under_legend(&g);
    // No numeric ticks on the position axis: the texts in the band under each plot are the
    // position names only (the numeric axis had -0.5, 0.5, 1.5, ... there).
    let texts = svg_texts(&svg);
    for (k, p) in g.iter().enumerate() {
        let under: Vec<&str> = texts
            .iter()
            .filter(|t| {
                t.0 >= p.plot.x0 && t.0 <= p.plot.x1 && t.1 > p.plot.y1 && t.1 <= p.plot.y1 + 20
            })
            .map(|t| t.2)
            .collect();
        assert_eq!(under, rins_scenarios::diagnose::POSITIONS, "panel {k}");
    }
    assert!(
        !texts
            .iter()
            .any(|t| t.2.starts_with("-0") && t.2.trim_start_matches(['-', '0', '.']).is_empty()),
        "a -0 tick"
    );
}

/// The position (x, y attributes) and text content of every `<text>` element of an SVG.
fn svg_texts(svg: &str) -> Vec<(i32, i32, &str)> {
    let attr = |t: &str, name: &str| -> Option<i32> {
        let i = t.find(&format!(" {name}=\""))? + name.len() + 3;
        t[i..i + t[i..].find('"')?]
            .parse::<f64>()
            .ok()
            .map(|v| v as i32)
    };
    svg.split("<text")
        .skip(1)
        .filter_map(|t| {
            let head = &t[..t.find('>')?];
            let body = &t[t.find('>')? + 1..];
            Some((
                attr(head, "x")?,
                attr(head, "y")?,
                body[..body.find("</text>")?].trim(),
            ))
        })
        .collect()
}

#[test]
fn week_long_figures_shrink_fivefold_as_envelopes_with_the_same_extremes() {
    let sc = rins_scenario::Scenario::load(Path::new("builtin:paper-16pos-week")).unwrap();
    let opt = rins_verification::paper::Table4Options {
        plant: sc.plant.clone(),
        runs: 1,
        duration_s: 7.0 * 86_400.0,
        compensation: None,
        nav: rins_experiments::NavRunConfig::default(),
    };
    let r = rins_verification::paper::table4(&opt, &|_| {});
    assert!(
        r.first_seed.uncompensated.len() > 10_000,
        "a week of records"
    );
    let env = paired_figures(&r, ["Figure 2", "Figure 3"], Kind::Envelope);
    let raw = paired_figures(&r, ["Figure 2", "Figure 3"], Kind::Solid);
    for (e, s) in env.iter().zip(&raw) {
        let (svg_e, g) = e.render().unwrap();
        let (svg_s, _) = s.render().unwrap();
        let ratio = svg_s.len() as f64 / svg_e.len() as f64;
        eprintln!(
            "{}: {} B every sample, {} B envelopes ({ratio:.1}x)",
            e.stem,
            svg_s.len(),
            svg_e.len()
        );
        assert!(ratio >= 5.0, "{}: only {ratio:.2}x smaller", e.stem);
        no_mark_under_legend(&g);
        text_at_least_8_pt(&e.stem, &svg_e);
        marks_keep_headroom(&e.stem, &g, false);
        // The compensated case is drawn after the uncompensated one, its mean line 1 px wide
        // inside the other's 3 px, so where the two coincide (Figure 2's east and north axes)
        // both show: every panel has both.
        let lines = |rgb: &str, w: &str| {
            svg_e
                .split("<polyline")
                .skip(1)
                .map(|t| &t[..t.find("/>").unwrap_or(t.len())])
                .filter(|t| t.contains(rgb) && t.contains(&format!("stroke-width=\"{w}\"")))
                .count()
        };
        let data: Vec<_> = e.panels.iter().map(data_range).collect();
        data_inside_padded_axes(&e.stem, &data, &g, None);
        // The panels of the two cases (the difference panel has neither).
        let n = e
            .panels
            .iter()
            .filter(|p| p.lines.iter().any(|l| l.label == "uncompensated"))
            .count();
        assert_eq!(n, 3, "{}: three axes or three position errors", e.stem);
        if e.stem.starts_with("fig2") {
            // Where the cases coincide (east, north) the difference panel shows what δβ
            // changes: per axis uncompensated − compensated at the same record, recomputed
            // here from the records, on a scale of its own.
            let series = if e.stem.ends_with("noise_free") {
                &r.noise_free_series
            } else {
                &r.first_seed
            };
            let diff = e.panels.last().unwrap();
            assert!(diff.title.contains("Difference"), "{}", diff.title);
            let labels: Vec<&str> = diff.lines.iter().map(|l| l.label).collect();
            assert_eq!(labels, ["East", "North", "Up"]);
            for (k, line) in diff.lines.iter().enumerate() {
                assert_eq!(line.points.len(), series.uncompensated.len());
                for i in [0, line.points.len() / 3, line.points.len() - 1] {
                    let (u, c) = (&series.uncompensated[i], &series.compensated[i]);
                    let want = u.att_err_rad[k].to_degrees() - c.att_err_rad[k].to_degrees();
                    assert_eq!(line.points[i], (u.t_s / 3600.0, want), "{k} {i}");
                }
            }
            let span = |p: &Panel| {
                let ((_, _), (lo, hi)) = data_range(p);
                hi - lo
            };
            let diff_axis = g.last().unwrap().axes.1;
            let case_axis = g[0].axes.1;
            eprintln!(
                "{}: east error spans {:.4} deg, the difference panel {:.4} deg (axis {:.4}, east axis {:.4})",
                e.stem,
                span(&e.panels[0]),
                span(diff),
                diff_axis.1 - diff_axis.0,
                case_axis.1 - case_axis.0
            );
        }
        assert!(
            lines("#C82828", "3") >= n && lines("#1E5AC8", "1") >= n,
            "{}: wide uncompensated {}, narrow compensated {} mean lines for {n} panels",
            e.stem,
            lines("#C82828", "3"),
            lines("#1E5AC8", "1")
        );
        for (panel, geo) in e.panels.iter().zip(&g) {
            let enveloped: Vec<_> = panel
                .lines
                .iter()
                .filter(|l| l.kind == Kind::Envelope)
                .collect();
            assert_eq!(enveloped.len(), geo.envelopes.len(), "{}", panel.title);
            for (line, cols) in enveloped.iter().zip(&geo.envelopes) {
                let ys = line.points.iter().map(|p| p.1);
                let (lo, hi) = ys.fold((f64::MAX, f64::MIN), |(a, b), y| (a.min(y), b.max(y)));
                let clo = cols.iter().map(|c| c.min).fold(f64::MAX, f64::min);
                let chi = cols.iter().map(|c| c.max).fold(f64::MIN, f64::max);
                assert_eq!((clo, chi), (lo, hi), "{}: {}", panel.title, line.label);
                assert!(cols.len() <= 450 && cols.len() * 20 < line.points.len());
            }
        }
    }
}

/// An asymmetric band (5 %, median, 95 %) is drawn with its dot at the estimate, not at the
/// band's centre: the sea figure's medians sat at the 5-95 % midpoint before `Kind::Interval`.
#[test]
fn interval_dots_sit_at_the_estimate_not_the_band_centre() {
    use rins_report::figures::plot::{Line, Panel, render_svg};
    // (low, estimate, high): the estimate at 10 %, 50 % and 90 % of each band.
    let bands = [(1.0, 1.4, 5.0), (2.0, 4.0, 6.0), (0.5, 3.2, 3.5)];
    let points: Vec<(f64, f64)> = bands
        .iter()
        .enumerate()
        .flat_map(|(k, &(lo, est, hi))| [(k as f64, lo), (k as f64, est), (k as f64, hi)])
        .collect();
    let panel = Panel::new(
        "bands",
        "value",
        vec![Line::new(
            "estimate",
            points,
            plotters::style::RED,
            Kind::Interval,
        )],
    )
    .categorical(&["a", "b", "c"]);
    let (_, g) = render_svg("t", "case", &[panel]).unwrap();
    let marks = &g[0].marks;
    let bars: Vec<_> = marks.iter().filter(|(a, b)| a.0 == b.0).collect();
    let dots: Vec<_> = marks
        .iter()
        .filter(|(a, b)| a.1 == b.1 && b.0 - a.0 == 2 * BAR_DOT_PX)
        .collect();
    assert_eq!((bars.len(), dots.len()), (3, 3), "{marks:?}");
    for ((bar, dot), &(lo, est, hi)) in bars.iter().zip(&dots).zip(&bands) {
        // Pixel y is linear in the value: the dot's place along the bar is the estimate's.
        let (y_lo, y_hi) = (bar.0.1 as f64, bar.1.1 as f64);
        let frac_px = (dot.0.1 as f64 - y_lo) / (y_hi - y_lo);
        let frac = (est - lo) / (hi - lo);
        let one_px = 1.0 / (y_hi - y_lo).abs();
        assert!(
            (frac_px - frac).abs() <= 1.5 * one_px,
            "dot at {frac_px:.3} of the bar, estimate at {frac:.3}"
        );
    }
}

/// `sea_end_error` as `rins paper sea` draws it, on made-up bands and noise-free values (the
/// drawing, not the study, is under test): text at least 8 pt at one column width, every bar
/// end and dot `HEADROOM_PX` inside the frame, the noise-free dots large and opaque.
#[test]
fn sea_end_error_is_print_sized_with_headroom_and_visible_dots() {
    use rins_scenarios::commands::sea::{
        END_ERROR_TITLE, END_ERROR_X, EndErrorData, end_error_panels,
    };
    use rins_verification::paper::Band;
    let band = |p05, median, p95| Band { median, p05, p95 };
    let data = vec![
        EndErrorData {
            case: "static reference",
            uncompensated_nm: band(7.58, 9.89, 14.19),
            compensated_nm: band(1.82, 4.07, 4.84),
            noise_free_nm: [9.32, 1.73],
        },
        EndErrorData {
            case: "ship",
            uncompensated_nm: band(1.98, 9.31, 12.83),
            compensated_nm: band(2.55, 4.27, 10.48),
            noise_free_nm: [8.06, 3.12],
        },
        EndErrorData {
            case: "ship + isolation",
            uncompensated_nm: band(4.56, 7.30, 10.39),
            compensated_nm: band(3.73, 5.86, 7.26),
            noise_free_nm: [7.50, 3.67],
        },
    ];
    let panels = end_error_panels(&data, 8);
    let (svg, g) =
        rins_report::figures::plot::render_svg(END_ERROR_TITLE, END_ERROR_X, &panels).unwrap();
    text_at_least_8_pt("sea_end_error", &svg);
    marks_keep_headroom("sea_end_error", &g, true);
    // The bands' 5 % and 95 % ends, from the data above (not from what was drawn).
    let ends: Vec<f64> = data
        .iter()
        .flat_map(|d| [&d.uncompensated_nm, &d.compensated_nm])
        .flat_map(|b| [b.p05, b.p95])
        .collect();
    let ranges: Vec<_> = panels.iter().map(data_range).collect();
    let lo = ends.iter().copied().fold(f64::MAX, f64::min);
    let hi = ends.iter().copied().fold(f64::MIN, f64::max);
    assert_eq!(
        ranges[0].1,
        (lo, hi),
        "the band panel's data are the band ends"
    );
    data_inside_padded_axes("sea_end_error", &ranges, &g, Some(HEADROOM_PX as f64));
    no_mark_under_legend(&g);
    // The noise-free dots: opaque, radius at least 8 px (1 mm at 3.5 in); the old ones were
    // 2 px at 45 % opacity.
    let circles: Vec<&str> = svg.split("<circle").skip(1).collect();
    let big = circles
        .iter()
        .filter(|c| {
            let r = c
                .find(" r=\"")
                .map(|i| &c[i + 4..])
                .and_then(|t| t[..t.find('"')?].parse::<f64>().ok());
            r.is_some_and(|r| r >= 8.0)
                && !c[..c.find("/>").unwrap_or(c.len())].contains("opacity=\"0.")
        })
        .count();
    assert!(big >= 6, "{big} large opaque dots (6 noise-free values)");
    let texts: Vec<String> = text_sizes_pt(&svg).into_iter().map(|t| t.1).collect();
    assert!(
        texts
            .iter()
            .any(|t| t.contains("every stochastic term off")),
        "the noise-free pair's name: {texts:?}"
    );
    assert!(!texts.iter().any(|t| t.contains("alone")), "{texts:?}");
}

/// A scatter (residual vs temperature: clusters at the two chamber temperatures) keeps its
/// outermost dots `HEADROOM_PX` off the left and right frame as well as top and bottom.
#[test]
fn scatter_clusters_keep_off_the_frame() {
    use rins_report::figures::plot::{Line, Panel, render_svg};
    // Two clusters at 23 and 63 °C, 60 points each (a dense scatter), plus a fitted curve.
    let pts: Vec<(f64, f64)> = (0..120)
        .map(|i| {
            let t = if i < 60 { 23.0 } else { 63.0 };
            (t + 0.01 * (i % 7) as f64, ((i * 37) % 11) as f64 - 5.0)
        })
        .collect();
    let fit = vec![(23.0, -1.0), (63.0, 1.0)];
    let panel = Panel::new(
        "gyro_x: residual",
        "residual (deg/h)",
        vec![
            Line::new("residual", pts, plotters::style::BLUE, Kind::Dots),
            Line::new("fit", fit, plotters::style::RED, Kind::Dashed),
        ],
    );
    let (svg, g) = render_svg("Residual vs temperature", "temperature (deg C)", &[panel]).unwrap();
    // The data by construction: x from 23.00 to 63.06 °C, y from -5 to 5 (all 11 residues).
    marks_keep_headroom("scatter", &g, true);
    // The clusters at 23 and 63 °C stand 5 % of the plot width off the side frames.
    let w = (g[0].plot.x1 - g[0].plot.x0) as f64;
    let data = [((23.0, 63.06), (-5.0, 5.0))];
    let (_, x_margin) = data_inside_padded_axes("scatter", &data, &g, Some(SCATTER_X_PAD_FRAC * w));
    assert!(x_margin >= SCATTER_X_PAD_FRAC * w - 1.0, "{x_margin} px");
    text_at_least_8_pt("scatter", &svg);
    assert!(svg.contains("temperature (°C)") && svg.contains("residual (°/h)"));
}

/// DejaVu Sans, which the PNG text is drawn with, has "µ" and "°": each draws differently from
/// a character the font lacks (drawn as the missing-glyph box) and from nothing.
#[test]
fn the_png_font_has_the_unit_glyphs() {
    use plotters::prelude::*;
    // The figures register the font on first use.
    let one = rins_report::figures::plot::Panel::new(
        "p",
        "y",
        vec![rins_report::figures::plot::Line::new(
            "",
            vec![(0.0, 0.0), (1.0, 1.0)],
            BLACK,
            Kind::Solid,
        )],
    );
    rins_report::figures::plot::render_svg("t", "x", &[one]).unwrap();
    let draw = |s: &str| {
        let mut buf = vec![0u8; 60 * 60 * 3];
        {
            let root = BitMapBackend::with_buffer(&mut buf, (60, 60)).into_drawing_area();
            root.fill(&WHITE).unwrap();
            root.draw(&Text::new(s.to_string(), (10, 10), ("sans-serif", 40)))
                .unwrap();
            root.present().unwrap();
        }
        buf
    };
    let (missing, blank) = (draw("\u{E000}"), draw(" "));
    for c in ["µ", "°", "g", "C"] {
        let b = draw(c);
        assert_ne!(b, blank, "{c} draws nothing");
        assert_ne!(b, missing, "{c} is the missing-glyph box");
    }
    assert_ne!(draw("µ"), draw("°"));
}

/// Issue 44: the iteration history's step axis is ticked at whole steps (it read 0.0, 0.5,
/// 1.0 for two steps): every x tick label of `iteration_history.svg` is a whole number, and
/// with few steps every step is ticked. The x tick labels are the rows of numeric texts that
/// share one y at several x (a y axis's labels share one x).
#[test]
fn the_iteration_history_ticks_whole_steps() {
    use rins_mvm::CHANNELS;
    use rins_mvm::iterate::{IterationReport, Level, Step};
    let dir = std::env::temp_dir().join(format!("rins-iter-ticks-{}", std::process::id()));
    for n in [2usize, 3, 4, 6, 13, 41] {
        let steps = (0..n)
            .map(|k| Step {
                step: k,
                levels: CHANNELS
                    .iter()
                    .enumerate()
                    .map(|(c, ch)| Level {
                        channel: ch.to_string(),
                        unit: "deg/h".into(),
                        residual_rms: 1.0,
                        noise_floor_rms: 1.0,
                        ratio: 1.0 + (c + 1) as f64 * 0.7 / (k + 1) as f64,
                    })
                    .collect(),
                flagged_cells: n - k,
                accepted: Vec::new(),
                coefficients: Vec::new(),
            })
            .collect();
        let report = IterationReport {
            source: "t.csv".into(),
            steps,
            reached_floor: false,
            stop: "test".into(),
            unexplained: Vec::new(),
            cells_before: Vec::new(),
            cells_after: Vec::new(),
            z_critical: 4.0,
            closest_to_gate: Vec::new(),
        };
        rins_report::iteration::write_figures(&dir, &report).unwrap();
        let svg = std::fs::read_to_string(dir.join("iteration_history.svg")).unwrap();
        let mut rows: std::collections::BTreeMap<i32, Vec<(i32, &str)>> = Default::default();
        for (x, y, t) in svg_texts(&svg) {
            if t.parse::<f64>().is_ok() {
                rows.entry(y).or_default().push((x, t));
            }
        }
        let x_rows: Vec<Vec<&str>> = rows
            .values()
            .filter(|r| r.len() >= 2 && r.iter().any(|(x, _)| *x != r[0].0))
            .map(|r| r.iter().map(|(_, t)| *t).collect())
            .collect();
        assert_eq!(
            x_rows.len(),
            2,
            "{n} steps: one step axis per panel: {rows:?}"
        );
        for labels in x_rows {
            assert!(
                labels.iter().all(|t| t.parse::<u64>().is_ok()),
                "{n} steps: a tick between steps: {labels:?}"
            );
            assert_eq!(labels.first(), Some(&"0"), "{n} steps: {labels:?}");
            if n <= 6 {
                let every: Vec<String> = (0..n).map(|k| k.to_string()).collect();
                assert_eq!(labels, every, "{n} steps: each step ticked");
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
