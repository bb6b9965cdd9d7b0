//! Navigation error series (Figures 2–3 counterparts): attitude, velocity and position errors and
//! the tRMS of Eq. 20, one entity group per case (`reference`, `uncompensated`, `compensated`).

use anyhow::Result;
use rerun::RecordingStream;
use rins_navigation::NavRecord;
use rins_navigation::errors::nmi;

use crate::series::{Series, nanos};

const ENU: [[u8; 3]; 3] = [[220, 50, 50], [50, 160, 50], [50, 90, 230]];

/// The four series of one navigation case under `nav/<case>/`.
pub struct NavSeries {
    att: Series,
    vel: Series,
    pos: Series,
    trms: Series,
}

impl NavSeries {
    /// Declares `nav/<case>/…`; `how` says how the rows are sampled (shown in the legend).
    pub fn new(rec: &RecordingStream, case: &str, how: &str) -> Result<Self> {
        let names = |q: [&str; 3], unit: &str| -> Vec<String> {
            q.iter().map(|c| format!("{c} ({how}), {unit}")).collect()
        };
        Ok(Self {
            att: Series::new(
                rec,
                format!("nav/{case}/attitude_error_deg"),
                &names(["East", "North", "Up"], "deg"),
                &ENU,
            )?,
            vel: Series::new(
                rec,
                format!("nav/{case}/velocity_error_mps"),
                &names(["East", "North", "Up"], "m/s"),
                &ENU,
            )?,
            pos: Series::new(
                rec,
                format!("nav/{case}/position_error_nmi"),
                &names(
                    ["latitude (north)", "longitude (east)", "horizontal"],
                    "nmi",
                ),
                &ENU,
            )?,
            trms: Series::new(
                rec,
                format!("nav/{case}/trms_nmi"),
                &[format!("tRMS of the horizontal error (Eq. 20, {how}), nmi")],
                &[[30, 30, 30]],
            )?,
        })
    }

    /// Adds a record at output sample `step` (its time is the record's).
    pub fn push(&mut self, rec: &RecordingStream, step: u64, r: &NavRecord) -> Result<()> {
        let t = nanos(r.t_s);
        let a = r.att_err_rad.map(f64::to_degrees);
        self.att.push(rec, step, t, &a)?;
        self.vel.push(rec, step, t, &r.vel_err_mps)?;
        self.pos.push(
            rec,
            step,
            t,
            &[nmi(r.north_m), nmi(r.east_m), nmi(r.horizontal_m)],
        )?;
        self.trms.push(rec, step, t, &[nmi(r.trms_m)])?;
        Ok(())
    }

    /// Sends the buffered rows.
    pub fn flush(&mut self, rec: &RecordingStream) -> Result<()> {
        for s in [&mut self.att, &mut self.vel, &mut self.pos, &mut self.trms] {
            s.flush(rec)?;
        }
        Ok(())
    }

    /// Logs a whole record series (a finished run), stepping by the record time and `dt_s`.
    pub fn log_all(
        rec: &RecordingStream,
        case: &str,
        how: &str,
        records: &[NavRecord],
        dt_s: f64,
    ) -> Result<()> {
        let mut s = Self::new(rec, case, how)?;
        for r in records {
            s.push(rec, (r.t_s / dt_s).round() as u64, r)?;
        }
        s.flush(rec)
    }
}
