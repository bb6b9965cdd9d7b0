//! A written log reads back through the diagnosis's own reader into the same history.

use rins_mvm::Attitude;
use rins_mvm_trials::{ChamberLeg, Design, HiddenEffect, generate, write_csv};

use super::base_model;

#[test]
fn csv_reads_back_into_the_same_history() {
    let mut design = Design::chamber_steps_four_azimuths();
    design.runs.truncate(3);
    for r in &mut design.runs {
        r.duration_s = 900.0;
        r.chamber[0] = match r.chamber[0] {
            ChamberLeg::Hold { temp_c, .. } => ChamberLeg::Hold {
                temp_c,
                dur_s: 100.0,
            },
            other => other,
        };
    }
    design.rate_hz = 5.0;
    let model = base_model();
    let h = generate(
        &model,
        &design,
        &[HiddenEffect::TempRateBias {
            dph_per_k_per_s: [50.0, 0.0, 0.0],
        }],
        3,
    );
    let dir = std::env::temp_dir().join(format!("rins-mvm-trials-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join("trial.csv");
    write_csv(&h, &path).expect("written");
    let m = rins_mvm::reader::read(&path).expect("the reader accepts it");
    let back = rins_mvm::to_history(m, "trial.csv").expect("a history");
    std::fs::remove_dir_all(&dir).ok();
    assert_eq!(back.t_s, h.t_s);
    assert_eq!(back.dtheta_rad, h.dtheta_rad);
    assert_eq!(back.dv_mps, h.dv_mps);
    assert_eq!(back.gyro_temp_c, h.gyro_temp_c);
    assert_eq!(back.housing_temp_c, h.housing_temp_c);
    assert_eq!(back.accel_temp_c, h.accel_temp_c);
    assert_eq!(back.run, h.run);
    assert_eq!(back.run_names, h.run_names);
    assert_eq!(back.segments, h.segments);
    // Angles go through degrees: equal to the last bits of the conversion.
    let (
        Attitude::Gimbal {
            outer_rad: o1,
            inner_rad: i1,
        },
        Attitude::Gimbal {
            outer_rad: o2,
            inner_rad: i2,
        },
    ) = (&h.attitude, &back.attitude)
    else {
        panic!("gimbal angles")
    };
    for (a, b) in o1.iter().zip(o2).chain(i1.iter().zip(i2)) {
        assert!(
            (a - b).abs() <= 4.0 * f64::EPSILON * a.abs().max(1.0),
            "{a} {b}"
        );
    }
}
