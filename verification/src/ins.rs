//! Closed-form free-inertial error responses of a static INS, reproduced by the full plant and
//! navigator (no rotation): the Schuler-averaged position responses to constant gyro biases,
//! the Schuler and Foucault periods, the bounded tilt ∇/g from an accelerometer bias, and the
//! position spread from angle random walk against covariance propagation of the linear model.

use nalgebra::{SMatrix, Vector3};
use rayon::prelude::*;
use rins_experiments::{NavRecord, NavRunConfig, run};
use rins_plant::earth::{OMEGA_IE_RPS, normal_gravity, radii_of_curvature};
use rins_plant::table::SchemeKind;
use rins_plant::units::{DPH, DPSH, UG};
use rins_plant::{Plant, PlantConfig};
use serde::Serialize;

/// A static, non-rotating plant with nothing on, at `rate_hz`.
pub fn static_plant(rate_hz: f64) -> PlantConfig {
    let mut c = PlantConfig {
        rate_hz,
        ..PlantConfig::default()
    };
    c.scheme.kind = SchemeKind::Static;
    c.thermal.enabled = false;
    c
}

/// Schuler-averaged position error (north, east in m) for gyro error ε (ENU, rad/s) at t:
/// δL(t) = −(ε_E/Ω) sin Ωt − ((sin L ε_N − cos L ε_U)/Ω)(1 − cos Ωt),
/// δλ(t) = (ε_N cos L + ε_U sin L) t − (tan L ε_E/Ω)(1 − cos Ωt) + tan L (sin L ε_N − cos L ε_U) sin(Ωt)/Ω.
pub fn gyro_bias_position(eps: &Vector3<f64>, lat: f64, t: f64) -> (f64, f64) {
    let w = OMEGA_IE_RPS;
    let (s, c, tn) = (lat.sin(), lat.cos(), lat.tan());
    let (wt_s, wt_c) = (w * t).sin_cos();
    let dl = -(eps.x / w) * wt_s - ((s * eps.y - c * eps.z) / w) * (1.0 - wt_c);
    let dlam = (eps.y * c + eps.z * s) * t - (tn * eps.x / w) * (1.0 - wt_c)
        + tn * (s * eps.y - c * eps.z) * wt_s / w;
    let (rm, rn) = radii_of_curvature(lat);
    (dl * rm, dlam * rn * c)
}

/// Schuler angular frequency √(g/R) with R the Gaussian mean radius at `lat`, rad/s.
pub fn schuler_rate(lat: f64) -> f64 {
    let (rm, rn) = radii_of_curvature(lat);
    (normal_gravity(lat, 0.0) / (rm * rn).sqrt()).sqrt()
}

/// One single-axis gyro-bias case.
#[derive(Clone, Debug, Serialize)]
pub struct GyroBiasCase {
    /// Axis with the bias (E, N or U: body = nav at position A).
    pub axis: String,
    /// Bias, °/h.
    pub bias_dph: f64,
    /// Duration, h.
    pub hours: f64,
    /// Largest |closed form| over the run (north, east), m.
    pub scale_m: [f64; 2],
    /// Largest |Schuler-averaged navigator − closed form| / scale (north, east).
    pub max_rel_dev: [f64; 2],
    /// End position error from the navigator (north, east), m.
    pub end_m: [f64; 2],
    /// End position error from the closed form (north, east), m.
    pub end_closed_form_m: [f64; 2],
}

fn moving_average(xs: &[f64], window: usize) -> Vec<f64> {
    let mut out = Vec::with_capacity(xs.len().saturating_sub(window) + 1);
    let mut sum: f64 = xs[..window].iter().sum();
    out.push(sum / window as f64);
    for k in window..xs.len() {
        sum += xs[k] - xs[k - window];
        out.push(sum / window as f64);
    }
    out
}

/// Static run with one gyro bias on `axis` for `hours`; the navigator's errors and the closed
/// form are both averaged over one Schuler period before comparison.
pub fn gyro_bias_case(axis: usize, bias_dph: f64, hours: f64, rate_hz: f64) -> GyroBiasCase {
    let mut cfg = static_plant(rate_hz);
    cfg.sensor.gyro.bias.enabled = true;
    cfg.sensor.gyro.bias.dph[axis] = bias_dph;
    let mut plant = Plant::new(&cfg).expect("valid");
    let rec_s = 10.0;
    let r = run(
        &mut plant,
        hours * 3600.0,
        &NavRunConfig {
            record_every_s: rec_s,
            ..NavRunConfig::default()
        },
    )
    .expect("run");
    let lat = plant.site().lat_rad;
    let mut eps = Vector3::zeros();
    eps[axis] = bias_dph * DPH;
    let window = (2.0 * std::f64::consts::PI / schuler_rate(lat) / rec_s).round() as usize;
    let series = |f: &dyn Fn(&NavRecord) -> f64| r.records.iter().map(f).collect::<Vec<f64>>();
    let nav_n = moving_average(&series(&|x| x.north_m), window);
    let nav_e = moving_average(&series(&|x| x.east_m), window);
    let cf_n = moving_average(&series(&|x| gyro_bias_position(&eps, lat, x.t_s).0), window);
    let cf_e = moving_average(&series(&|x| gyro_bias_position(&eps, lat, x.t_s).1), window);
    let scale = |v: &[f64]| v.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let dev = |a: &[f64], b: &[f64]| {
        a.iter()
            .zip(b)
            .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()))
    };
    let (sn, se) = (scale(&cf_n), scale(&cf_e));
    let end = r.end();
    let cf_end = gyro_bias_position(&eps, lat, end.t_s);
    GyroBiasCase {
        axis: ["east", "north", "up"][axis].into(),
        bias_dph,
        hours,
        scale_m: [sn, se],
        max_rel_dev: [
            dev(&nav_n, &cf_n) / sn.max(1.0),
            dev(&nav_e, &cf_e) / se.max(1.0),
        ],
        end_m: [end.north_m, end.east_m],
        end_closed_form_m: [cf_end.0, cf_end.1],
    }
}

/// Accelerometer-bias case: Schuler and Foucault periods and the bounded tilt.
#[derive(Clone, Debug, Serialize)]
pub struct AccelBiasCase {
    /// East accelerometer bias, µg.
    pub bias_ug: f64,
    /// Schuler period measured from the east-velocity zero crossings, min.
    pub schuler_period_min: f64,
    /// 2π/√(g/R), min.
    pub schuler_period_expected_min: f64,
    /// Foucault period from the rotation of the Schuler oscillation between E and N, h.
    pub foucault_period_h: f64,
    /// 2π/(Ω sin L), h.
    pub foucault_period_expected_h: f64,
    /// Mean north tilt φ_N over the run, rad.
    pub mean_tilt_rad: f64,
    /// ∇_E/g, rad.
    pub expected_tilt_rad: f64,
    /// Largest |φ_N| over the run relative to 2∇/g (the tilt stays bounded).
    pub max_tilt_over_2_nabla_g: f64,
}

/// Static run with an east accelerometer bias for `hours`.
pub fn accel_bias_case(bias_ug: f64, hours: f64, rate_hz: f64) -> AccelBiasCase {
    let mut cfg = static_plant(rate_hz);
    cfg.sensor.accel.bias.enabled = true;
    cfg.sensor.accel.bias.ug = [bias_ug, 0.0, 0.0];
    let mut plant = Plant::new(&cfg).expect("valid");
    let rec_s = 5.0;
    let r = run(
        &mut plant,
        hours * 3600.0,
        &NavRunConfig {
            record_every_s: rec_s,
            ..NavRunConfig::default()
        },
    )
    .expect("run");
    let lat = plant.site().lat_rad;
    let ws = schuler_rate(lat);
    let ve: Vec<f64> = r.records.iter().map(|x| x.vel_err_mps[0]).collect();
    let vn: Vec<f64> = r.records.iter().map(|x| x.vel_err_mps[1]).collect();
    // Schuler period from the first zero crossings of v_E (interpolated), before Foucault turns
    // the oscillation into the north channel.
    let mut crossings = Vec::new();
    for k in 1..ve.len() {
        if ve[k - 1] * ve[k] < 0.0 && (k as f64 * rec_s) < 6.0 * 3600.0 {
            let f = ve[k - 1] / (ve[k - 1] - ve[k]);
            crossings.push((k as f64 - 1.0 + f) * rec_s);
        }
    }
    let half_periods = crossings.len().saturating_sub(1).max(1) as f64;
    let schuler_period =
        2.0 * (crossings.last().unwrap_or(&0.0) - crossings.first().unwrap_or(&0.0)) / half_periods;
    // Foucault: project (v_E, v_N) on the Schuler oscillation over each period; the angle of
    // the oscillation plane turns at Ω sin L. Least-squares slope of the unwrapped angle.
    let per = (2.0 * std::f64::consts::PI / ws / rec_s).round() as usize;
    let mut angles = Vec::new();
    let mut reference: Option<(f64, f64)> = None;
    for (c, (e, n)) in ve.chunks(per).zip(vn.chunks(per)).enumerate() {
        if e.len() < per {
            break;
        }
        let t0 = (c * per) as f64 * rec_s;
        let amp = |v: &[f64]| {
            let (mut a, mut b) = (0.0, 0.0);
            for (k, x) in v.iter().enumerate() {
                let (s, cc) = (ws * (t0 + (k as f64 + 1.0) * rec_s)).sin_cos();
                a += x * s;
                b += x * cc;
            }
            (a, b)
        };
        let (ea, eb) = amp(e);
        let (na, nb) = amp(n);
        // Both channels projected on one fixed Schuler phase (the east channel's in the first
        // period), so the sign changes as the oscillation turns from east to north are kept.
        let (r0, r1) = *reference.get_or_insert_with(|| {
            let m = ea.hypot(eb).max(1e-300);
            (ea / m, eb / m)
        });
        angles.push((
            t0 + 0.5 * per as f64 * rec_s,
            (na * r0 + nb * r1).atan2(ea * r0 + eb * r1),
        ));
    }
    let mut unwrapped: Vec<(f64, f64)> = Vec::new();
    for (t, a) in angles {
        let mut a = a;
        if let Some(&(_, prev)) = unwrapped.last() {
            while a - prev > std::f64::consts::PI {
                a -= 2.0 * std::f64::consts::PI;
            }
            while a - prev < -std::f64::consts::PI {
                a += 2.0 * std::f64::consts::PI;
            }
        }
        unwrapped.push((t, a));
    }
    let n = unwrapped.len() as f64;
    let (mt, ma) = unwrapped
        .iter()
        .fold((0.0, 0.0), |(st, sa), (t, a)| (st + t / n, sa + a / n));
    let (num, den) = unwrapped.iter().fold((0.0, 0.0), |(nu, de), (t, a)| {
        (nu + (t - mt) * (a - ma), de + (t - mt) * (t - mt))
    });
    let slope = (num / den).abs();
    let g = normal_gravity(lat, 0.0);
    let phin: Vec<f64> = r.records.iter().map(|x| x.att_err_rad[1]).collect();
    let mean_tilt = phin.iter().sum::<f64>() / phin.len() as f64;
    let nabla = bias_ug * UG;
    AccelBiasCase {
        bias_ug,
        schuler_period_min: schuler_period / 60.0,
        schuler_period_expected_min: 2.0 * std::f64::consts::PI / ws / 60.0,
        foucault_period_h: 2.0 * std::f64::consts::PI / slope / 3600.0,
        foucault_period_expected_h: 2.0 * std::f64::consts::PI
            / (OMEGA_IE_RPS * lat.sin())
            / 3600.0,
        mean_tilt_rad: mean_tilt,
        expected_tilt_rad: nabla / g,
        max_tilt_over_2_nabla_g: phin.iter().fold(0.0_f64, |m, x| m.max(x.abs()))
            / (2.0 * nabla / g),
    }
}

/// Angle-random-walk Monte Carlo against the linear model's covariance.
#[derive(Clone, Debug, Serialize)]
pub struct ArwCase {
    /// ARW, °/√h.
    pub arw_dpsh: f64,
    /// Runs.
    pub runs: usize,
    /// Duration, h.
    pub hours: f64,
    /// Monte Carlo 1σ of the end error (north, east), m.
    pub mc_sigma_m: [f64; 2],
    /// Analytic 1σ (north, east), m.
    pub analytic_sigma_m: [f64; 2],
    /// Analytic 1σ after one week (north, east), m, for reference.
    pub analytic_week_sigma_m: [f64; 2],
}

/// The linear static INS error model's matrix F (ψ-angle form, vertical channel held), states
/// [φE, φN, φU, δvE, δvN, δL, δλ]: φ̇ = −ω_ie × φ + δω_ie(δL) + δω_en(δv) − ε and
/// δv̇ = f × φ − 2ω_ie × δv + ∇. Shared by the ARW covariance here and by the schemes analysis
/// (`rins-schemes`), which drives it with a scheme's residual.
pub fn static_error_matrix(lat: f64) -> SMatrix<f64, 7, 7> {
    let w = OMEGA_IE_RPS;
    let (s, c) = lat.sin_cos();
    let (rm, rn) = radii_of_curvature(lat);
    let r = (rm * rn).sqrt();
    let g = normal_gravity(lat, 0.0);
    let mut f = SMatrix::<f64, 7, 7>::zeros();
    // φ̇ = −ω_ie × φ + δω_ie(δL) + δω_en(δv) − ε
    let om = Vector3::new(0.0, w * c, w * s);
    f.fixed_view_mut::<3, 3>(0, 0)
        .copy_from(&(-om.cross_matrix()));
    f[(0, 4)] = -1.0 / r;
    f[(1, 3)] = 1.0 / r;
    f[(2, 3)] = s / c / r;
    f[(1, 5)] = -w * s;
    f[(2, 5)] = w * c;
    // δv̇ = f × φ − 2ω_ie × δv
    f[(3, 1)] = -g;
    f[(4, 0)] = g;
    f[(3, 4)] = 2.0 * w * s;
    f[(4, 3)] = -2.0 * w * s;
    // position
    f[(5, 4)] = 1.0 / rm;
    f[(6, 3)] = 1.0 / (rn * c);
    f
}

/// Linear static INS error model ([`static_error_matrix`]) driven by white gyro noise of
/// density `arw` (rad/√s) on each axis; returns the position 1σ (north, east) in m after
/// `hours`, by covariance propagation with a 1 s step.
pub fn arw_position_sigma(arw: f64, lat: f64, hours: f64) -> (f64, f64) {
    let (rm, rn) = radii_of_curvature(lat);
    let c = lat.cos();
    let f = static_error_matrix(lat);
    let h = 1.0;
    let fh = f * h;
    let mut phi = SMatrix::<f64, 7, 7>::identity();
    let mut term = SMatrix::<f64, 7, 7>::identity();
    for k in 1..12 {
        term = term * fh / k as f64;
        phi += term;
    }
    let mut q = SMatrix::<f64, 7, 7>::zeros();
    for i in 0..3 {
        q[(i, i)] = arw * arw * h;
    }
    // Midpoint-rule discrete noise: Φ(h/2) Q Φ(h/2)ᵀ ≈ Q to O(h·|F|), |F| ~ 1e-3 1/s.
    let mut p = SMatrix::<f64, 7, 7>::zeros();
    for _ in 0..(hours * 3600.0 / h).round() as usize {
        p = phi * p * phi.transpose() + q;
    }
    (p[(5, 5)].sqrt() * rm, p[(6, 6)].sqrt() * rn * c)
}

/// Monte Carlo of `runs` seeds (both cores) with ARW only, `hours` long at `rate_hz`.
pub fn arw_case(arw_dpsh: f64, runs: usize, hours: f64, rate_hz: f64) -> ArwCase {
    let ends: Vec<(f64, f64)> = (0..runs as u64)
        .into_par_iter()
        .map(|seed| {
            let mut cfg = static_plant(rate_hz);
            cfg.seed = 1000 + seed;
            cfg.sensor.gyro.angle_random_walk.enabled = true;
            cfg.sensor.gyro.angle_random_walk.dpsh = [arw_dpsh; 3];
            let mut plant = Plant::new(&cfg).expect("valid");
            let e = run(
                &mut plant,
                hours * 3600.0,
                &NavRunConfig {
                    record_every_s: 3600.0,
                    ..NavRunConfig::default()
                },
            )
            .expect("run")
            .end();
            (e.north_m, e.east_m)
        })
        .collect();
    let sd = |v: Vec<f64>| {
        let n = v.len() as f64;
        let m = v.iter().sum::<f64>() / n;
        (v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (n - 1.0)).sqrt()
    };
    let lat = 36.6f64.to_radians();
    let arw = arw_dpsh * DPSH;
    let (an, ae) = arw_position_sigma(arw, lat, hours);
    let (wn, we) = arw_position_sigma(arw, lat, 168.0);
    ArwCase {
        arw_dpsh,
        runs,
        hours,
        mc_sigma_m: [
            sd(ends.iter().map(|e| e.0).collect()),
            sd(ends.iter().map(|e| e.1).collect()),
        ],
        analytic_sigma_m: [an, ae],
        analytic_week_sigma_m: [wn, we],
    }
}

/// `rins verify ins`: every closed-form case with pass/fail checks.
#[derive(Clone, Debug, Serialize)]
pub struct InsReport {
    /// East, north and up gyro bias over a week.
    pub gyro_bias: Vec<GyroBiasCase>,
    /// East accelerometer bias.
    pub accel_bias: AccelBiasCase,
    /// ARW Monte Carlo.
    pub arw: ArwCase,
    /// Checks.
    pub checks: Vec<crate::report::Check>,
}

impl InsReport {
    /// Runs every case: 0.01 °/h gyro biases for a week, 50 µg for 30 h, ARW 0.003 °/√h with
    /// `arw_runs` seeds for 12 h. Static cases run at 20 Hz and the Monte Carlo at 10 Hz: with a
    /// static, non-rotating IMU the rate changes nothing but the cost.
    pub fn run(arw_runs: usize) -> Self {
        use crate::report::Check;
        let gyro_bias: Vec<GyroBiasCase> = (0..3usize)
            .into_par_iter()
            .map(|a| gyro_bias_case(a, 0.01, 168.0, 20.0))
            .collect();
        let accel_bias = accel_bias_case(50.0, 30.0, 20.0);
        let arw = arw_case(0.003, arw_runs, 12.0, 10.0);
        let mut checks = Vec::new();
        for c in &gyro_bias {
            checks.push(Check::at_most(
                &format!(
                    "gyro {} bias: Schuler-averaged deviation (fraction)",
                    c.axis
                ),
                c.max_rel_dev[0].max(c.max_rel_dev[1]),
                0.03,
            ));
        }
        let a = &accel_bias;
        checks.push(Check::at_most(
            "Schuler period relative error",
            (a.schuler_period_min / a.schuler_period_expected_min - 1.0).abs(),
            0.005,
        ));
        checks.push(Check::at_most(
            "Foucault period relative error",
            (a.foucault_period_h / a.foucault_period_expected_h - 1.0).abs(),
            0.02,
        ));
        checks.push(Check::at_most(
            "mean tilt vs nabla/g relative error",
            (a.mean_tilt_rad / a.expected_tilt_rad - 1.0).abs(),
            0.02,
        ));
        checks.push(Check::at_most(
            "tilt bounded by 2 nabla/g",
            a.max_tilt_over_2_nabla_g,
            1.05,
        ));
        // The sample std of n draws has a relative spread of ~1/sqrt(2(n-1)): allow 3 of those.
        let tol = 3.0 / (2.0 * (arw.runs as f64 - 1.0)).sqrt();
        for (k, axis) in ["north", "east"].iter().enumerate() {
            checks.push(Check::at_most(
                &format!("ARW {axis} 1-sigma: |MC/analytic - 1|"),
                (arw.mc_sigma_m[k] / arw.analytic_sigma_m[k] - 1.0).abs(),
                tol,
            ));
        }
        Self {
            gyro_bias,
            accel_bias,
            arw,
            checks,
        }
    }

    /// Whether every check passed.
    pub fn passed(&self) -> bool {
        self.checks.iter().all(|c| c.pass)
    }

    /// Text rendering.
    pub fn to_text(&self) -> String {
        let mut s = String::from(
            "Static free-inertial responses, plant + navigator vs closed form (36.6 N)\n",
        );
        for c in &self.gyro_bias {
            s += &format!(
                "  {:>5} gyro {} deg/h, {} h: end north {:9.1} m (cf {:9.1}), east {:9.1} m (cf {:9.1}); max deviation {:.2} % / {:.2} %\n",
                c.axis,
                c.bias_dph,
                c.hours,
                c.end_m[0],
                c.end_closed_form_m[0],
                c.end_m[1],
                c.end_closed_form_m[1],
                100.0 * c.max_rel_dev[0],
                100.0 * c.max_rel_dev[1]
            );
        }
        let a = &self.accel_bias;
        s += &format!(
            "  east accel {} ug: Schuler {:.2} min (expected {:.2}), Foucault {:.2} h (expected {:.2}), mean tilt {:.4e} rad (nabla/g {:.4e})\n",
            a.bias_ug,
            a.schuler_period_min,
            a.schuler_period_expected_min,
            a.foucault_period_h,
            a.foucault_period_expected_h,
            a.mean_tilt_rad,
            a.expected_tilt_rad
        );
        let w = &self.arw;
        s += &format!(
            "  ARW {} deg/rt-h, {} runs x {} h: 1-sigma north {:.0} m / east {:.0} m, analytic {:.0} / {:.0} m; after a week (analytic) {:.0} / {:.0} m\n",
            w.arw_dpsh,
            w.runs,
            w.hours,
            w.mc_sigma_m[0],
            w.mc_sigma_m[1],
            w.analytic_sigma_m[0],
            w.analytic_sigma_m[1],
            w.analytic_week_sigma_m[0],
            w.analytic_week_sigma_m[1]
        );
        s += "Checks\n";
        for c in &self.checks {
            s += &format!(
                "  [{}] {:<52} {:10.3e} <= {:.3e}\n",
                if c.pass { "pass" } else { "FAIL" },
                c.name,
                c.value,
                c.limit
            );
        }
        s
    }
}
