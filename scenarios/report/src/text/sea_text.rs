//! Text of `rins paper sea`: per case (static reference, ship, ship with azimuth isolation)
//! the horizontal error at the end over the seeds and the compensation's improvement, then the
//! noise-free pair's signed latitude and longitude errors with its horizontal error and δβ's
//! own effect (the columns of the at-sea table in docs/carrier.md), then the ideal IMU.

use std::fmt::Write;

use rins_verification::paper::SeaReport;

use super::RenderText;
use super::table4_text::NOISE_FREE;

impl RenderText for SeaReport {
    fn render_text(&self) -> String {
        let mut s = String::new();
        // Writing to a String cannot fail.
        let _ = writeln!(
            s,
            "At sea: {} seeds x {:.2} days, 16-position RINS, Table 3 sensors (wall {:.1} s)",
            self.runs, self.days, self.wall_s
        );
        let _ = writeln!(
            s,
            "  sea: {}",
            match self.sea_seed {
                Some(seed) => format!("one realisation for every seed (sea seed {seed})"),
                None => "each seed its own realisation (from its run seed)".into(),
            }
        );
        let _ = writeln!(
            s,
            "  horizontal error at the end (nmi), median [5%, 95%] over the seeds; improvement of the medians by the compensation\n  {:<24} {:>30} {:>30} {:>21}",
            "case", "uncompensated", "compensated", "impr. % hor (lon)"
        );
        for (name, r) in self.cases() {
            let (u, c) = (&r.uncompensated.horizontal_nm, &r.compensated.horizontal_nm);
            let _ = writeln!(
                s,
                "  {:<24} {:>9.4} [{:>8.4}, {:>8.4}] {:>9.4} [{:>8.4}, {:>8.4}] {:>12.2} ({:.2})",
                name,
                u.median,
                u.p05,
                u.p95,
                c.median,
                c.p05,
                c.p95,
                r.improvement_pct.horizontal,
                r.improvement_pct.lon
            );
        }
        let _ = writeln!(
            s,
            "  {NOISE_FREE}: signed end errors (nmi; latitude north +, longitude east +) and dbeta's own effect (uncompensated - compensated)\n  {:<24} {:>29} {:>29} {:>19}",
            "case", "uncompensated lat lon hor", "compensated lat lon hor", "dbeta lat lon"
        );
        for (name, r) in self.cases() {
            let (u, c) = (&r.noise_free.uncompensated, &r.noise_free.compensated);
            let _ = writeln!(
                s,
                "  {:<24} {:>+9.4} {:>+9.4} {:>9.4} {:>+9.4} {:>+9.4} {:>9.4} {:>+9.4} {:>+9.4}",
                name,
                u.lat_nm,
                u.lon_nm,
                u.horizontal_nm,
                c.lat_nm,
                c.lon_nm,
                c.horizontal_nm,
                u.lat_nm - c.lat_nm,
                u.lon_nm - c.lon_nm
            );
        }
        let _ = writeln!(
            s,
            "  ideal IMU on the ship: max horizontal {:.3} m / {:.3} m, max attitude {:.2e} / {:.2e} rad (isolation off / on)",
            self.ideal[0].max_horizontal_m,
            self.ideal[1].max_horizontal_m,
            self.ideal[0].max_attitude_rad,
            self.ideal[1].max_attitude_rad
        );
        s
    }
}
