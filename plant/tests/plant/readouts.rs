//! The unit's measured outputs beside the increments: gimbal encoder angles and temperature
//! sensor readings, each error term against its closed form with the plant otherwise as built.

use rins_plant::table::SchemeKind;
use rins_plant::thermal::node;
use rins_plant::units::{ARCSEC, PPM};
use rins_plant::{Plant, PlantConfig};

/// The 16-position scheme with the paper's sensors, shortened dwells so the table turns often.
fn turning() -> PlantConfig {
    let mut c = rins_plant::presets::paper_16pos_config();
    c.scheme.kind = SchemeKind::SixteenPosition;
    c.scheme.dwell_s = 5.0;
    c.thermal.chamber.profile = vec![[0.0, 20.0], [600.0, 40.0]];
    c
}

#[test]
fn ideal_readouts_are_the_true_angles_and_temperatures() {
    let mut p = Plant::new(&turning()).unwrap();
    for _ in 0..20_000 {
        let s = p.step();
        let t = p.truth();
        assert_eq!(s.encoder, t.gimbal.angles);
        assert_eq!(s.temps_c, t.temps.nodes_c);
    }
}

#[test]
fn encoder_offset_scale_and_resolution_follow_the_closed_form() {
    let (s_ppm, b_arcsec, res_arcsec) = ([150.0, -80.0], [12.0, -30.0], [1.25, 0.5]);
    let mut c = turning();
    let e = &mut c.sensor.encoder;
    e.scale_factor.enabled = true;
    e.scale_factor.ppm = s_ppm;
    e.offset.enabled = true;
    e.offset.arcsec = b_arcsec;
    let mut p = Plant::new(&c).unwrap();
    let mut c_q = c.clone();
    c_q.sensor.encoder.quantization.enabled = true;
    c_q.sensor.encoder.quantization.resolution_arcsec = res_arcsec;
    let mut q = Plant::new(&c_q).unwrap();
    let (mut sq, mut n, mut moving) = ([0.0f64; 2], [0u64; 2], 0u64);
    let mut prev = [f64::NAN; 2];
    for _ in 0..60_000 {
        let (a, b) = (p.step(), q.step());
        let truth = p.truth().gimbal;
        moving += truth.moving as u64;
        let th = [truth.angles.outer_rad, truth.angles.inner_rad];
        let got = [a.encoder.outer_rad, a.encoder.inner_rad];
        let got_q = [b.encoder.outer_rad, b.encoder.inner_rad];
        for k in 0..2 {
            // Linear part: (1 + s)·θ + b, exact to rounding.
            let lin = (1.0 + s_ppm[k] * PPM) * th[k] + b_arcsec[k] * ARCSEC;
            assert!((got[k] - lin).abs() <= 4.0 * f64::EPSILON * th[k].abs().max(1.0));
            // Resolution: a whole number of counts, within half a count of the linear reading.
            let r = res_arcsec[k] * ARCSEC;
            let counts = got_q[k] / r;
            assert!((counts - counts.round()).abs() < 1e-6, "not a whole count");
            assert!((got_q[k] - lin).abs() <= 0.5 * r * (1.0 + 1e-9));
            // Only while this gimbal turns (one turns at a time; the other holds one count).
            if th[k] != prev[k] {
                sq[k] += (got_q[k] - lin).powi(2);
                n[k] += 1;
            }
        }
        prev = th;
    }
    assert!(
        moving > 10_000,
        "the table must turn for the statistics to mean anything"
    );
    // While the table turns the angles sweep many counts and the rounding error is uniform:
    // RMS = r/√12 (within 10 %).
    for k in 0..2 {
        let rms = (sq[k] / n[k] as f64).sqrt();
        let expect = res_arcsec[k] * ARCSEC / 12f64.sqrt();
        assert!(
            (rms / expect - 1.0).abs() < 0.1,
            "gimbal {k}: {rms} vs {expect}"
        );
    }
}

#[test]
fn temperature_sensor_offset_noise_and_resolution_follow_the_closed_form() {
    let offset_k = [0.3, -0.2, 0.1, 0.0, 0.5, -0.4];
    let sigma_k = [0.05, 0.1, 0.2, 0.05, 0.1, 0.02];
    let mut c = turning();
    c.thermal.step_s = 1.0;
    let t = &mut c.sensor.temperature;
    t.offset.enabled = true;
    t.offset.k = offset_k;
    t.noise.enabled = true;
    t.noise.sigma_k = sigma_k;
    let mut p = Plant::new(&c).unwrap();
    let mut plain = Plant::new(&turning()).unwrap();
    let (mut sum, mut sq, mut readings) = ([0.0; 6], [0.0; 6], 0.0);
    let mut last = None;
    for k in 0..200_000u64 {
        let (s, s0) = (p.step(), plain.step());
        // Sensor errors change no other output: the increments are those of the plain plant.
        assert_eq!((s.dtheta_rad, s.dv_mps), (s0.dtheta_rad, s0.dv_mps));
        // Held between thermal updates (every 100 samples at 100 Hz and a 1 s step).
        if k % 100 != 0 {
            assert_eq!(
                Some(s.temps_c),
                last,
                "reading changed between updates at {k}"
            );
            continue;
        }
        last = Some(s.temps_c);
        let tr = p.truth().temps.nodes_c;
        readings += 1.0;
        for i in 0..node::COUNT {
            let e = s.temps_c[i] - tr[i] - offset_k[i];
            sum[i] += e;
            sq[i] += e * e;
        }
    }
    for i in 0..node::COUNT {
        let mean = sum[i] / readings;
        let sd = (sq[i] / readings - mean * mean).sqrt();
        // 2000 readings: the mean within 4σ/√n, the spread within 8 % of σ.
        assert!(
            mean.abs() < 4.0 * sigma_k[i] / readings.sqrt(),
            "sensor {i} mean {mean}"
        );
        assert!((sd / sigma_k[i] - 1.0).abs() < 0.08, "sensor {i} sd {sd}");
    }

    let mut c = turning();
    c.sensor.temperature.resolution.enabled = true;
    c.sensor.temperature.resolution.lsb_k = 0.0625;
    let mut p = Plant::new(&c).unwrap();
    for _ in 0..50_000 {
        let s = p.step();
        let tr = p.truth().temps.nodes_c;
        for (reading, truth) in s.temps_c.iter().zip(&tr) {
            let counts = reading / 0.0625;
            assert_eq!(counts, counts.round());
            assert!((reading - truth).abs() <= 0.03125);
        }
    }
}

#[test]
fn readout_errors_resume_bit_identically_from_a_saved_state() {
    let mut c = turning();
    c.sensor.temperature.noise.enabled = true;
    c.sensor.temperature.noise.sigma_k = [0.1; 6];
    c.sensor.encoder.quantization.enabled = true;
    let run = |p: &mut Plant, n: usize| -> Vec<u64> {
        (0..n)
            .flat_map(|_| {
                let s = p.step();
                let mut v = vec![s.encoder.outer_rad, s.encoder.inner_rad];
                v.extend(s.temps_c);
                v.into_iter().map(f64::to_bits).collect::<Vec<_>>()
            })
            .collect()
    };
    let mut a = Plant::new(&c).unwrap();
    run(&mut a, 12_345);
    let bytes = a.serialize_state();
    let expected = run(&mut a, 5_000);
    let mut b = Plant::from_serialized_state(&c, &bytes).unwrap();
    assert_eq!(run(&mut b, 5_000), expected);
    // A reseed gives the temperature sensors a new realisation too.
    let mut r = Plant::from_serialized_state(&c, &bytes).unwrap();
    r.reseed_noise(77);
    assert_ne!(run(&mut r, 5_000), expected);
}
