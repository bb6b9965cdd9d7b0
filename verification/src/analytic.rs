//! Analytic checks of the rotation scheme: the cancellation of Eq. 8 and the δβ residual of
//! Eq. 11, integrated from the plant's own schedule and error model.

use nalgebra::{Matrix3, Vector3};
use rins_plant::effects::{AccelModel, AccelSpec, GyroModel, GyroSpec, TermContext};
use rins_plant::table::{Schedule, SchemeSpec, body_to_nav, gimbal_body_rate};
use rins_plant::units::{DEG, DPH};
use serde::Serialize;

use crate::quadrature::integrate;

/// Gauss–Legendre pieces per motion segment (moves span up to π of rotation).
const PIECES_MOVE: usize = 16;

/// The plant's instantaneous state at time `t` for the analytic integrals: no Earth rate,
/// constant temperature (δβ and the Eq. 3/4 terms do not depend on it at the reference).
fn context(sched: &Schedule, t: f64, gravity: f64) -> (Matrix3<f64>, TermContext) {
    let g = sched.eval(t);
    let c_bn = body_to_nav(&Matrix3::identity(), g.angles);
    let c_nb = c_bn.transpose();
    let omega_b = gimbal_body_rate(g.angles.inner_rad, g.outer_rate_rps, g.inner_rate_rps);
    let f_b = c_nb * Vector3::new(0.0, 0.0, gravity);
    // dt = 1 s and increments equal to the rates: the increment-error model returns rates.
    let ctx = TermContext {
        dt_s: 1.0,
        dtheta_rad: omega_b,
        dv_mps: f_b,
        f_b_mps2: f_b,
        up_b: c_nb.column(2).into_owned(),
        north_b: c_nb.column(1).into_owned(),
        east_b: c_nb.column(0).into_owned(),
        gyro_temp_c: Vector3::repeat(25.0),
        gyro_gradient_k: Vector3::zeros(),
        accel_temp_c: 25.0,
    };
    (c_bn, ctx)
}

/// Which part of the cycle to integrate.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Phase {
    All,
    Stationary,
    Rotation,
}

/// ∫ f(t) over one cycle of `sched`, split at every motion breakpoint, restricted to `phase`.
/// Returns (∫f, ∫|f|).
fn over_cycle<F: FnMut(f64) -> Vector3<f64>>(
    sched: &Schedule,
    phase: Phase,
    mut f: F,
) -> (Vector3<f64>, f64) {
    let lead = sched.lead_s();
    let mut sum = Vector3::zeros();
    let mut mag = 0.0;
    for (_, bp, end) in sched.step_times_s() {
        let mut pieces: Vec<(f64, f64, usize, bool)> = vec![
            (bp[0], bp[1], 4, true),
            (bp[1], bp[2], PIECES_MOVE, true),
            (bp[2], bp[3], 4, true),
        ];
        pieces.push((bp[3], end, 1, false));
        for (a, b, n, moving) in pieces {
            if (phase == Phase::Stationary && moving) || (phase == Phase::Rotation && !moving) {
                continue;
            }
            sum += integrate(lead + a, lead + b, n, &mut f);
            mag += integrate(lead + a, lead + b, n, |t| {
                Vector3::new(f(t).norm(), 0.0, 0.0)
            })
            .x;
        }
    }
    (sum, mag)
}

/// Eq. 8 for one error set.
#[derive(Clone, Debug, Serialize)]
pub struct CancellationCase {
    /// Which errors are on.
    pub errors: String,
    /// Table acceleration limit, °/s² (`inf` = constant-rate moves).
    pub accel_dps2: f64,
    /// φ = ∫ C_b^n·δ dt over one cycle (rad for gyros, m/s for accelerometers).
    pub integral: [f64; 3],
    /// |φ| / ∫|C_b^n·δ| dt: the fraction of the error that survives the cycle. For the
    /// accelerometers only the horizontal (E, N) part of φ counts; see [`AccelVertical`].
    pub cancellation_ratio: f64,
}

/// The accelerometer scale-factor error on gravity is rectified, not modulated: its vertical
/// component g·Σᵢ S_i (C_b^n)₃ᵢ² ≥ 0 survives any rotation. With constant-rate moves the cycle
/// integral is g·[S_z(16 T_s + 12 T_r) + S_y·4 T_r] (x never tilts toward vertical).
#[derive(Clone, Debug, Serialize)]
pub struct AccelVertical {
    /// Numeric vertical integral over one cycle, m/s (constant-rate moves).
    pub numeric_mps: f64,
    /// Closed form, m/s.
    pub closed_form_mps: f64,
    /// Relative difference.
    pub rel_err: f64,
    /// The same mean over the cycle as an equivalent vertical bias, µg.
    pub equivalent_bias_ug: f64,
}

/// Eq. 8 results.
#[derive(Clone, Debug, Serialize)]
pub struct Eq8Report {
    /// Worst ratio over every case.
    pub cancellation_ratio: f64,
    /// Largest |φ| over the gyro cases, rad.
    pub phi_abs_rad: f64,
    /// Cycle duration, s.
    pub cycle_s: f64,
    /// Each case.
    pub cases: Vec<CancellationCase>,
    /// The rectified vertical accelerometer scale-factor term.
    pub accel_scale_factor_vertical: AccelVertical,
}

fn table3_gyro(which: &str) -> GyroSpec {
    let mut g = GyroSpec::default();
    if which == "bias" || which == "all" {
        g.bias.enabled = true;
        g.bias.dph = [0.01, -0.007, 0.013];
    }
    if which == "scale_factor" || which == "all" {
        g.scale_factor.enabled = true;
        g.scale_factor.ppm = [5.0, -3.0, 4.0];
    }
    if which == "misalignment" || which == "all" {
        g.misalignment.enabled = true;
        g.misalignment.arcsec = [5.0, -4.0, 3.0, 6.0, -2.0, 5.0];
    }
    g
}

fn table3_accel(which: &str) -> AccelSpec {
    let mut a = AccelSpec::default();
    if which == "bias" || which == "all" {
        a.bias.enabled = true;
        a.bias.ug = [50.0, -40.0, 30.0];
    }
    if which == "scale_factor" || which == "all" {
        a.scale_factor.enabled = true;
        a.scale_factor.ppm = [50.0, -30.0, 40.0];
    }
    if which == "misalignment" || which == "all" {
        a.misalignment.enabled = true;
        a.misalignment.arcsec = [5.0, -4.0, 3.0, 6.0, -2.0, 5.0];
    }
    a
}

/// Eq. 8: over one 16-position cycle, constant bias, scale factor and misalignment (Table 3
/// magnitudes, mixed signs) integrate to zero in the navigation frame. Done for gyros and
/// accelerometers, with constant-rate moves and with the plant's default acceleration limit.
pub fn eq8() -> Eq8Report {
    let gravity = 9.8;
    let mut cases = Vec::new();
    let mut cycle_s = 0.0;
    for accel in [f64::INFINITY, SchemeSpec::default().accel_dps2] {
        let sched = Schedule::new(
            &SchemeSpec {
                accel_dps2: accel,
                ..SchemeSpec::default()
            }
            .resolve(),
        );
        cycle_s = sched.cycle_s();
        for which in ["bias", "scale_factor", "misalignment", "all"] {
            let gm = GyroModel::new(&table3_gyro(which));
            let (phi, mag) = over_cycle(&sched, Phase::All, |t| {
                let (c, ctx) = context(&sched, t, gravity);
                c * gm.increment_error(
                    &ctx,
                    &mut [Vector3::zeros(); rins_plant::effects::gyro::GYRO_TERMS],
                )
            });
            cases.push(CancellationCase {
                errors: format!("gyro {which}"),
                accel_dps2: accel,
                integral: phi.into(),
                cancellation_ratio: phi.norm() / mag,
            });
            let am = AccelModel::new(&table3_accel(which));
            let (dv, mag) = over_cycle(&sched, Phase::All, |t| {
                let (c, ctx) = context(&sched, t, gravity);
                c * am.increment_error(&ctx, &mut [Vector3::zeros(); 6])
            });
            let horizontal = dv.xy().norm();
            cases.push(CancellationCase {
                errors: format!("accel {which}"),
                accel_dps2: accel,
                integral: dv.into(),
                cancellation_ratio: horizontal / mag,
            });
        }
    }
    let sched = Schedule::new(
        &SchemeSpec {
            accel_dps2: f64::INFINITY,
            ..SchemeSpec::default()
        }
        .resolve(),
    );
    let spec = table3_accel("scale_factor");
    let am = AccelModel::new(&spec);
    let (dv, _) = over_cycle(&sched, Phase::All, |t| {
        let (c, ctx) = context(&sched, t, gravity);
        c * am.increment_error(&ctx, &mut [Vector3::zeros(); 6])
    });
    let s = spec.scale_factor.ppm.map(|p| p * 1e-6);
    let d = SchemeSpec::default();
    let (ts, tr) = (d.dwell_s, 180.0 / d.rate_dps);
    let closed = gravity * (s[2] * (16.0 * ts + 12.0 * tr) + s[1] * 4.0 * tr);
    let accel_scale_factor_vertical = AccelVertical {
        numeric_mps: dv.z,
        closed_form_mps: closed,
        rel_err: ((dv.z - closed) / closed).abs(),
        equivalent_bias_ug: dv.z / sched.cycle_s() / rins_plant::units::UG,
    };
    Eq8Report {
        accel_scale_factor_vertical,
        cancellation_ratio: cases
            .iter()
            .map(|c| c.cancellation_ratio)
            .fold(0.0, f64::max),
        phi_abs_rad: cases
            .iter()
            .filter(|c| c.errors.starts_with("gyro"))
            .map(|c| Vector3::from(c.integral).norm())
            .fold(0.0, f64::max),
        cycle_s,
        cases,
    }
}

/// Eq. 11 results.
#[derive(Clone, Debug, Serialize)]
pub struct Eq11Report {
    /// δβ used, °/h.
    pub delta_beta_dph: [f64; 3],
    /// Dwell time T_s, s.
    pub dwell_s: f64,
    /// ∫ over the stationary phases of one cycle, rad.
    pub stationary_rad: [f64; 3],
    /// The paper's −8·T_s·δβ_z, rad.
    pub expected_z_rad: f64,
    /// The same in degrees (paper: ≈ 0.002° for T_s = 180 s, δβ_z = 0.005 °/h).
    pub expected_z_deg: f64,
    /// Relative error of the stationary z term against −8·T_s·δβ_z.
    pub stationary_z_rel_err: f64,
    /// max(|x|, |y|) / |z| of the stationary integral.
    pub stationary_xy_over_z: f64,
    /// ∫ over the rotation phases (constant-rate moves as in Eq. 6), numeric, rad.
    pub rotation_rad: [f64; 3],
    /// The same from the closed form for the cosine transition, rad.
    pub rotation_closed_form_rad: [f64; 3],
    /// |numeric − closed form| / |closed form|.
    pub rotation_rel_err: f64,
    /// Full-cycle residual (stationary + rotation), rad.
    pub full_cycle_rad: [f64; 3],
    /// Rotation phases with the plant's default acceleration limit, numeric, rad.
    pub rotation_accel_limited_rad: [f64; 3],
    /// Whether the paper's statement that the rotation phases cancel holds for this model.
    pub rotation_phases_cancel: bool,
}

/// Closed form of ∫ C_b^n δβ w dt over one constant-rate move of `angle` (±π) about body unit
/// axis `a` starting from attitude `c0`, with w = (1 − u)/2 and u = (C_b^n)₃₃.
/// With K = [a]×, R(θ) = A₀ + cosθ·A_c + sinθ·A_s (A₀ = I + K², A_c = −K², A_s = K), so u and w
/// are affine in cosθ and sinθ and the integrand is a quadratic trigonometric polynomial:
/// ∫₀^π {1, c, s, c², s², sc} dθ = {π, 0, 2, π/2, π/2, 0}.
pub fn rotation_closed_form(
    c0: &Matrix3<f64>,
    a: &Vector3<f64>,
    rate_rps: f64,
    dbeta: &Vector3<f64>,
) -> Vector3<f64> {
    let k = a.cross_matrix();
    let a0 = Matrix3::identity() + k * k;
    let ac = -(k * k);
    let as_ = k;
    let (u0, uc, us) = ((c0 * a0)[(2, 2)], (c0 * ac)[(2, 2)], (c0 * as_)[(2, 2)]);
    let (w0, wc, ws) = (0.5 * (1.0 - u0), -0.5 * uc, -0.5 * us);
    let pi = std::f64::consts::PI;
    let m =
        a0 * (w0 * pi) + (a0 * ws + as_ * w0) * 2.0 + ac * (wc * pi / 2.0) + as_ * (ws * pi / 2.0);
    c0 * m * dbeta / rate_rps
}

/// Eq. 11: with only δβ on (cosine transition), the stationary phases give [0, 0, −8·T_s·δβ_z];
/// the rotation phases are integrated numerically and in closed form.
pub fn eq11(delta_beta_dph: [f64; 3], dwell_s: f64) -> Eq11Report {
    let mut g = GyroSpec::default();
    g.position_bias.enabled = true;
    g.position_bias.dph = delta_beta_dph;
    let gm = GyroModel::new(&g);
    let spec = SchemeSpec {
        accel_dps2: f64::INFINITY,
        dwell_s,
        ..SchemeSpec::default()
    };
    let sched = Schedule::new(&spec.resolve());
    let gm = &gm;
    let integrand = |sched: &Schedule| {
        let sched = sched.clone();
        move |t: f64| {
            let (c, ctx) = context(&sched, t, 9.8);
            c * gm.increment_error(
                &ctx,
                &mut [Vector3::zeros(); rins_plant::effects::gyro::GYRO_TERMS],
            )
        }
    };
    let (stationary, _) = over_cycle(&sched, Phase::Stationary, integrand(&sched));
    let (rotation, _) = over_cycle(&sched, Phase::Rotation, integrand(&sched));

    // Closed form, move by move, from the plant's own schedule (start attitude, body axis).
    let dbeta = Vector3::from(delta_beta_dph) * DPH;
    let rate = spec.rate_dps * DEG;
    let mut closed = Vector3::zeros();
    for (start, _, _) in sched.step_times_s() {
        let t0 = sched.lead_s() + start;
        // Just after the move starts the table turns at ±ω_r about one body axis.
        let moving = sched.eval(t0 + 1e-6);
        let c0 = body_to_nav(&Matrix3::identity(), sched.eval(t0).angles);
        let axis_b = gimbal_body_rate(
            moving.angles.inner_rad,
            moving.outer_rate_rps,
            moving.inner_rate_rps,
        );
        closed += rotation_closed_form(&c0, &axis_b.normalize(), rate, &dbeta);
    }

    let limited = Schedule::new(
        &SchemeSpec {
            dwell_s,
            ..SchemeSpec::default()
        }
        .resolve(),
    );
    let (rot_lim, _) = over_cycle(&limited, Phase::Rotation, integrand(&limited));

    let expected = -8.0 * dwell_s * dbeta.z;
    Eq11Report {
        delta_beta_dph,
        dwell_s,
        stationary_rad: stationary.into(),
        expected_z_rad: expected,
        expected_z_deg: expected.to_degrees(),
        stationary_z_rel_err: ((stationary.z - expected) / expected).abs(),
        stationary_xy_over_z: stationary.x.abs().max(stationary.y.abs()) / stationary.z.abs(),
        rotation_rad: rotation.into(),
        rotation_closed_form_rad: closed.into(),
        rotation_rel_err: (rotation - closed).norm() / closed.norm().max(f64::MIN_POSITIVE),
        full_cycle_rad: (stationary + rotation).into(),
        rotation_accel_limited_rad: rot_lim.into(),
        rotation_phases_cancel: rotation.norm() <= 1e-9 * expected.abs(),
    }
}

/// One sample of [`cycle_trace`].
#[derive(Clone, Copy, Debug, Serialize)]
pub struct CyclePoint {
    /// Time since the cycle start, s.
    pub t_s: f64,
    /// φ from the constant bias so far (E, N, U), rad.
    pub bias_rad: [f64; 3],
    /// φ from the position-dependent bias δβ so far (E, N, U), rad.
    pub delta_beta_rad: [f64; 3],
}

/// φ(t) = ∫₀ᵗ C_b^n·δ dt through one cycle of the 16-position scheme with constant-rate moves
/// (as Eq. 6; no Earth rate), by the midpoint rule with step `dt_s`: for a constant gyro bias
/// `bias_dph` it returns to zero at the cycle end (Eq. 8), for δβ it ends near
/// [0, 0, −8·T_s·δβ_z] plus the rotation-phase term (Eq. 11). For figures; [`eq8`] and [`eq11`]
/// integrate the same quantities exactly by quadrature.
pub fn cycle_trace(
    bias_dph: [f64; 3],
    delta_beta_dph: [f64; 3],
    dwell_s: f64,
    dt_s: f64,
) -> Vec<CyclePoint> {
    let mut gb = GyroSpec::default();
    gb.bias.enabled = true;
    gb.bias.dph = bias_dph;
    let mut gd = GyroSpec::default();
    gd.position_bias.enabled = true;
    gd.position_bias.dph = delta_beta_dph;
    let (mb, md) = (GyroModel::new(&gb), GyroModel::new(&gd));
    let spec = SchemeSpec {
        accel_dps2: f64::INFINITY,
        dwell_s,
        ..SchemeSpec::default()
    };
    let sched = Schedule::new(&spec.resolve());
    let n = (sched.cycle_s() / dt_s).round() as usize;
    let dt = sched.cycle_s() / n as f64;
    let (mut pb, mut pd) = (Vector3::zeros(), Vector3::zeros());
    let mut out = Vec::with_capacity(n + 1);
    out.push(CyclePoint {
        t_s: 0.0,
        bias_rad: [0.0; 3],
        delta_beta_rad: [0.0; 3],
    });
    let mut terms = [Vector3::zeros(); rins_plant::effects::gyro::GYRO_TERMS];
    for k in 0..n {
        let (c, ctx) = context(&sched, sched.lead_s() + (k as f64 + 0.5) * dt, 9.8);
        pb += c * mb.increment_error(&ctx, &mut terms) * dt;
        pd += c * md.increment_error(&ctx, &mut terms) * dt;
        out.push(CyclePoint {
            t_s: (k + 1) as f64 * dt,
            bias_rad: pb.into(),
            delta_beta_rad: pd.into(),
        });
    }
    out
}
