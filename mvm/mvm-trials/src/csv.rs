//! A history as a measurement CSV file (docs/measurement-format.md), so a failing trial can be
//! replayed alone with `rins diagnose --data FILE`. Numbers are printed with `{:e}`, the
//! shortest form that reads back to the same f64; angles in degrees.

use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::Path;

use rins_mvm::{Attitude, History};

/// Writes `h` to `path`: a `run` label column (one segment per run: write each run as one
/// segment), `t_s`, the increments, the attitude (`outer_deg`, `inner_deg` or `q_bn_*`) and
/// the temperatures `temp_gyro_{x,y,z}_c`, `temp_housing_c` (when present) and `temp_accel_c`.
pub fn write_csv(h: &History, path: impl AsRef<Path>) -> io::Result<()> {
    let mut f = BufWriter::new(File::create(path)?);
    writeln!(f, "# rins-mvm-trials: {}", h.source.replace('\n', " "))?;
    let mut header = vec![
        "run",
        "t_s",
        "dtheta_x_rad",
        "dtheta_y_rad",
        "dtheta_z_rad",
        "dv_x_mps",
        "dv_y_mps",
        "dv_z_mps",
    ];
    match &h.attitude {
        Attitude::Gimbal { .. } => header.extend(["outer_deg", "inner_deg"]),
        Attitude::Quaternion(_) => header.extend(["q_bn_w", "q_bn_x", "q_bn_y", "q_bn_z"]),
    }
    header.extend(["temp_gyro_x_c", "temp_gyro_y_c", "temp_gyro_z_c"]);
    if h.housing_temp_c.is_some() {
        header.push("temp_housing_c");
    }
    header.push("temp_accel_c");
    writeln!(f, "{}", header.join(","))?;
    for k in 0..h.len() {
        write!(f, "{},{:e}", h.run_names[h.run[k] as usize], h.t_s[k])?;
        for x in h.dtheta_rad.iter().chain(&h.dv_mps) {
            write!(f, ",{:e}", x[k])?;
        }
        match &h.attitude {
            Attitude::Gimbal {
                outer_rad,
                inner_rad,
            } => write!(
                f,
                ",{:e},{:e}",
                outer_rad[k].to_degrees(),
                inner_rad[k].to_degrees()
            )?,
            Attitude::Quaternion(q) => write!(
                f,
                ",{:e},{:e},{:e},{:e}",
                q[k][0], q[k][1], q[k][2], q[k][3]
            )?,
        }
        for t in &h.gyro_temp_c {
            write!(f, ",{:e}", t[k])?;
        }
        if let Some(t) = &h.housing_temp_c {
            write!(f, ",{:e}", t[k])?;
        }
        writeln!(f, ",{:e}", h.accel_temp_c[k])?;
    }
    f.flush()
}
