//! Table 2 of the paper as printed, compared entry by entry with the plant's kinematics.

use nalgebra::Matrix3;
use rins_plant::table::{Schedule, SchemeSpec, body_to_nav};
use serde::Serialize;

/// Table 2 transcribed: entry tokens in terms of c = cos(ω_r t), s = sin(ω_r t).
pub const PRINTED: [[[&str; 3]; 3]; 16] = [
    [["c", "-s", "0"], ["s", "c", "0"], ["0", "0", "1"]],
    [["-1", "0", "0"], ["0", "-c", "s"], ["0", "s", "c"]],
    [["-c", "-s", "0"], ["-s", "c", "0"], ["0", "0", "1"]],
    [["1", "0", "0"], ["0", "-c", "-s"], ["0", "s", "-c"]],
    [["1", "0", "0"], ["0", "c", "s"], ["0", "-s", "c"]],
    [["c", "s", "0"], ["s", "-c", "0"], ["0", "0", "1"]],
    [["-1", "0", "0"], ["0", "c", "-s"], ["0", "-s", "-c"]],
    [["-c", "s", "0"], ["-s", "-c", "0"], ["0", "0", "1"]],
    [["c", "s", "0"], ["-s", "c", "0"], ["0", "0", "1"]],
    [["-1", "0", "0"], ["0", "-c", "-s"], ["0", "-s", "c"]],
    [["-c", "s", "0"], ["s", "c", "0"], ["0", "0", "-1"]],
    [["1", "0", "0"], ["0", "-c", "s"], ["0", "-s", "-c"]],
    [["1", "0", "0"], ["0", "c", "-s"], ["0", "s", "c"]],
    [["c", "-s", "0"], ["-s", "-c", "0"], ["0", "0", "-1"]],
    [["-1", "0", "0"], ["0", "c", "s"], ["0", "s", "-c"]],
    [["-c", "-s", "0"], ["s", "-c", "0"], ["0", "0", "1"]],
];

fn eval_token(tok: &str, c: f64, s: f64) -> f64 {
    match tok {
        "c" => c,
        "-c" => -c,
        "s" => s,
        "-s" => -s,
        "0" => 0.0,
        "1" => 1.0,
        "-1" => -1.0,
        _ => unreachable!("Table 2 uses only ±c, ±s, 0, ±1"),
    }
}

/// The printed matrix of sequence `seq` (1-based) at rotation angle `theta`.
pub fn printed(seq: usize, theta: f64) -> Matrix3<f64> {
    let (s, c) = theta.sin_cos();
    Matrix3::from_fn(|i, j| eval_token(PRINTED[seq - 1][i][j], c, s))
}

/// One disagreement between the printed table and the kinematics.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Mismatch {
    /// Sequence 1–16.
    pub sequence: usize,
    /// Row 1–3.
    pub row: usize,
    /// Column 1–3.
    pub col: usize,
    /// Printed expression.
    pub printed_expr: String,
    /// Printed value at the probe angle.
    pub printed: f64,
    /// Value from the kinematics of Eq. 5–6 at the probe angle.
    pub derived: f64,
    /// Probe angle ω_r t, degrees.
    pub probe_deg: f64,
}

/// Result of the comparison.
#[derive(Clone, Debug, Serialize)]
pub struct Table2Report {
    /// Entries compared (16 sequences × 9 entries × probes).
    pub entries_compared: usize,
    /// Every disagreement (reported once per entry, at the first probe where it shows).
    pub mismatches: Vec<Mismatch>,
    /// Largest difference on the entries that agree.
    pub max_abs_diff_agreeing: f64,
}

/// Evaluates each sequence's C_b^n(t) from the plant's schedule (constant-rate moves as in
/// Eq. 6) at several angles and compares with the printed table.
pub fn compare() -> Table2Report {
    let spec = SchemeSpec {
        accel_dps2: f64::INFINITY,
        ..SchemeSpec::default()
    };
    let rate = spec.rate_dps.to_radians();
    let sched = Schedule::new(&spec.resolve());
    let probes_deg: [f64; 3] = [17.0, 60.0, 135.0];
    let mut mismatches: Vec<Mismatch> = Vec::new();
    let mut max_ok: f64 = 0.0;
    let mut compared = 0;
    for (seq, (start, _, _)) in sched.step_times_s().into_iter().enumerate() {
        let seq = seq + 1;
        for &p in &probes_deg {
            let theta = p.to_radians();
            let t = sched.lead_s() + start + theta / rate;
            let derived = body_to_nav(&Matrix3::identity(), sched.eval(t).angles);
            let print = printed(seq, theta);
            for i in 0..3 {
                for j in 0..3 {
                    compared += 1;
                    let d = (derived[(i, j)] - print[(i, j)]).abs();
                    if d > 1e-9 {
                        if !mismatches
                            .iter()
                            .any(|m| m.sequence == seq && m.row == i + 1 && m.col == j + 1)
                        {
                            mismatches.push(Mismatch {
                                sequence: seq,
                                row: i + 1,
                                col: j + 1,
                                printed_expr: PRINTED[seq - 1][i][j].into(),
                                printed: print[(i, j)],
                                derived: derived[(i, j)],
                                probe_deg: p,
                            });
                        }
                    } else {
                        max_ok = max_ok.max(d);
                    }
                }
            }
        }
    }
    Table2Report {
        entries_compared: compared,
        mismatches,
        max_abs_diff_agreeing: max_ok,
    }
}
