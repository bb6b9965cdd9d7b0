//! The figure rules (`figures::rules`) on real results, checked on the geometry the plotting
//! code placed (not by eye): `bias_by_position` has a categorical position axis and no legend
//! box covers a plotted mark; the week-long paper figures shrink at least 5× as envelopes, and
//! each envelope's extremes are the series' extremes.

use std::path::{Path, PathBuf};

use rins_scenarios::commands::measure::{MeasureArgs, run as measure};
use rins_scenarios::figures::paper::paired_figures;
use rins_scenarios::figures::plot::{Kind, PanelGeometry};

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
    let model = rins_scenarios::Scenario::load(&docs("diagnosis-model.toml")).unwrap();
    let m = rins_mvm::reader::read(&data).unwrap();
    let h = rins_mvm::to_history(m, "unit").unwrap();
    let opts = rins_mvm::Options {
        diagnose: true,
        ..Default::default()
    };
    let an = rins_mvm::analyse(&model.plant, &h, &opts);
    assert!(an.after().is_some(), "the hidden effect is fitted");
    let (svg, g) = rins_scenarios::diagnose::render_bias_by_position(&an).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(g.len(), 6, "one panel per channel");
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
    let sc = rins_scenarios::Scenario::load(Path::new("builtin:paper-16pos-week")).unwrap();
    let opt = rins_verify::paper::Table4Options {
        plant: sc.plant.clone(),
        runs: 1,
        duration_s: 7.0 * 86_400.0,
        compensation: None,
        nav: rins_experiments::NavRunConfig::default(),
    };
    let r = rins_verify::paper::table4(&opt, &|_| {});
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
    use rins_scenarios::figures::plot::{Line, Panel, render_svg};
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
        .filter(|(a, b)| a.1 == b.1 && b.0 - a.0 == 6)
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
