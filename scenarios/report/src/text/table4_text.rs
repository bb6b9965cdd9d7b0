//! Text of `rins paper table4` (and of `rins paper`'s Table 4 part): the end-of-run errors over
//! the seeds beside the paper's values, the improvement, and the noise-free pair.

use std::fmt::Write;

use rins_verification::paper::{Band, Table4Report, paired_table_header, published};

use super::RenderText;

/// The name of the deterministic pair wherever it is printed or drawn: every stochastic term
/// off, the same run with and without the δβ compensation. Both runs keep the other
/// deterministic errors (bias, scale factor, misalignment), so the pair's difference, not
/// either run, is δβ's own effect.
pub const NOISE_FREE: &str = "noise-free pair (every stochastic term off)";

impl RenderText for Table4Report {
    fn render_text(&self) -> String {
        let (u, c) = (&self.uncompensated, &self.compensated);
        let row = |name: &str, paper: [f64; 2], bu: &Band, bc: &Band| {
            let p = |x: f64| {
                if x.is_nan() {
                    "-".to_string()
                } else {
                    format!("{x:.4}")
                }
            };
            format!(
                "  {:<26} {:>9} {:>9}   {:>8.4} [{:>7.4}, {:>7.4}]   {:>8.4} [{:>7.4}, {:>7.4}]\n",
                name,
                p(paper[0]),
                p(paper[1]),
                bu.median,
                bu.p05,
                bu.p95,
                bc.median,
                bc.p05,
                bc.p95
            )
        };
        let na = [f64::NAN, f64::NAN];
        let mut s = format!(
            "Table 4: {} seeds x {:.2} days, 16-position RINS at 36.6 N 123.6 E, Table 3 sensors (wall {:.1} s)\n\
             (navigator updated every {} IMU interval(s), vertical channel held at the site height; paper values where the paper gives them)\n",
            self.runs, self.days, self.wall_s, self.nav_subsamples,
        );
        s += &paired_table_header(28);
        s += &row(
            "|latitude error| (nmi)",
            published::LAT_NM,
            &u.abs_lat_nm,
            &c.abs_lat_nm,
        );
        s += &row(
            "|longitude error| (nmi)",
            published::LON_NM,
            &u.abs_lon_nm,
            &c.abs_lon_nm,
        );
        s += &row("latitude error (nmi)", na, &u.lat_nm, &c.lat_nm);
        s += &row("longitude error (nmi)", na, &u.lon_nm, &c.lon_nm);
        s += &row(
            "horizontal error (nmi)",
            na,
            &u.horizontal_nm,
            &c.horizontal_nm,
        );
        s += &row("tRMS (nmi)", na, &u.trms_nm, &c.trms_nm);
        s += &row(
            "up-axis mean |att| (deg)",
            published::UP_ATT_MEAN_DEG,
            &u.up_att_mean_deg,
            &c.up_att_mean_deg,
        );
        let i = &self.improvement_pct;
        // Writing to a String cannot fail.
        let _ = writeln!(
            s,
            "  improvement (medians):    latitude {:.2} % (paper 0.53 %), longitude {:.2} % (paper 59.44 %), horizontal {:.2} %, tRMS {:.2} %, up attitude {:.2} % (paper 10.65 %)",
            i.lat, i.lon, i.horizontal, i.trms, i.up_att_mean
        );
        let (nu, nc) = (&self.noise_free.uncompensated, &self.noise_free.compensated);
        let _ = writeln!(
            s,
            "  {NOISE_FREE}: uncompensated lat {:+.4} lon {:+.4} hor {:.4} nmi, up att {:.4} deg; compensated lat {:+.4} lon {:+.4} hor {:.4} nmi, up att {:.4} deg",
            nu.lat_nm,
            nu.lon_nm,
            nu.horizontal_nm,
            nu.up_att_mean_deg,
            nc.lat_nm,
            nc.lon_nm,
            nc.horizontal_nm,
            nc.up_att_mean_deg
        );
        let _ = writeln!(
            s,
            "  dbeta's own effect (the pair's difference, unc - comp): lat {:+.4} lon {:+.4} nmi",
            nu.lat_nm - nc.lat_nm,
            nu.lon_nm - nc.lon_nm
        );
        s
    }
}
