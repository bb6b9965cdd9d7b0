//! Figures of the paired paper studies (`rins paper table4|table5`): the Figure 2 (attitude
//! error) and Figure 3 (position error, tRMS of Eq. 20) counterparts, uncompensated against
//! compensated, for the first seed and the noise-free pair. Table 5's Figures 9-10 are the same
//! drawings of its runs.

use std::path::Path;

use anyhow::Result;
use plotters::style::RGBColor;
use rins_nav::NavRecord;
use rins_verify::paper::Table4Report;

use super::plot::{Line, Panel, write_svg};

/// Uncompensated case.
const UNC: RGBColor = RGBColor(200, 40, 40);
/// Compensated case.
const COMP: RGBColor = RGBColor(30, 90, 200);

/// Writes `fig2_attitude_error{,_noise_free}.svg` and `fig3_position_error{,_noise_free}.svg`
/// (with PNGs) into `out`.
pub fn write_table4_figures(r: &Table4Report, out: &Path) -> Result<()> {
    for (series, tag, what) in [
        (&r.first_seed, "", "first seed"),
        (&r.noise_free_series, "_noise_free", "noise-free"),
    ] {
        let pts = |recs: &[NavRecord], f: &dyn Fn(&NavRecord) -> f64| -> Vec<(f64, f64)> {
            recs.iter().map(|x| (x.t_s / 3600.0, f(x))).collect()
        };
        let pair = |f: &dyn Fn(&NavRecord) -> f64| {
            vec![
                Line {
                    label: "uncompensated",
                    points: pts(&series.uncompensated, f),
                    color: UNC,
                    error_bars: false,
                },
                Line {
                    label: "compensated",
                    points: pts(&series.compensated, f),
                    color: COMP,
                    error_bars: false,
                },
            ]
        };
        let att = ["East", "North", "Up"]
            .iter()
            .enumerate()
            .map(|(k, n)| Panel {
                title: format!("{n}-axis attitude error"),
                y_label: "deg",
                lines: pair(&|x| x.att_err_rad[k].to_degrees()),
            })
            .collect::<Vec<_>>();
        write_svg(
            &out.join(format!("fig2_attitude_error{tag}.svg")),
            &format!("Figure 2 counterpart: attitude error ({what})"),
            "time (h)",
            &att,
        )?;
        let nm = rins_nav::errors::nmi;
        let pos = vec![
            Panel {
                title: "Latitude error".into(),
                y_label: "nmi",
                lines: pair(&|x| nm(x.north_m)),
            },
            Panel {
                title: "Longitude error".into(),
                y_label: "nmi",
                lines: pair(&|x| nm(x.east_m)),
            },
            Panel {
                title: "Horizontal error and tRMS (Eq. 20)".into(),
                y_label: "nmi",
                lines: {
                    let mut l = pair(&|x| nm(x.horizontal_m));
                    l.push(Line {
                        label: "tRMS uncompensated",
                        points: pts(&series.uncompensated, &|x| nm(x.trms_m)),
                        color: RGBColor(240, 150, 150),
                        error_bars: false,
                    });
                    l.push(Line {
                        label: "tRMS compensated",
                        points: pts(&series.compensated, &|x| nm(x.trms_m)),
                        color: RGBColor(140, 170, 240),
                        error_bars: false,
                    });
                    l
                },
            },
        ];
        write_svg(
            &out.join(format!("fig3_position_error{tag}.svg")),
            &format!("Figure 3 counterpart: position error ({what})"),
            "time (h)",
            &pos,
        )?;
    }
    Ok(())
}
