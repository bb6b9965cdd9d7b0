//! Static figures: `rins run --figures` bucket means against the closed-form Earth rate, and the
//! SVG and PNG files are real (PNG signature and size, SVG text with the titles).

use rins_scenario::Scenario;
use rins_scenarios::sinks::RunFigures;

const STATIC_IDEAL: &str = r#"
[scenario]
name = "static-ideal"
duration_s = 30.0
[site]
lat_deg = 36.6
lon_deg = 123.6
height_m = 0.0
[scheme]
kind = "static"
[sensor]
preset = "ideal"
[thermal]
chamber = { temp_c = 25.0 }
"#;

#[test]
fn run_figures_show_the_earth_rate_and_write_svg_and_png() {
    let sc = Scenario::from_toml(STATIC_IDEAL, "static-ideal").unwrap();
    let n = sc.samples();
    let mut figs = RunFigures::new(&sc.plant, n);
    rins_scenarios::run(&sc, n, &mut [&mut figs]).unwrap();
    // Position A with a level vehicle at azimuth 0: body = ENU, so the gyros read the Earth
    // rate (0, Ω cos L, Ω sin L), Ω = 7.292115e-5 rad/s = 15.0411 deg/h.
    let omega_dph = 7.292115e-5_f64.to_degrees() * 3600.0;
    let lat = 36.6_f64.to_radians();
    let expect = [0.0, omega_dph * lat.cos(), omega_dph * lat.sin()];
    let rates = figs.rates_dph();
    assert!(rates.len() >= 1000, "{} buckets", rates.len());
    for (t, r) in &rates {
        for i in 0..3 {
            assert!(
                (r[i] - expect[i]).abs() < 1e-6,
                "t = {t}: axis {i}: {} vs {}",
                r[i],
                expect[i]
            );
        }
    }
    let dir = std::env::temp_dir().join(format!("rins-figures-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let files = figs.write(&dir, "static-ideal").unwrap();
    assert_eq!(files.len(), 6);
    for f in &files {
        let bytes = std::fs::read(f).unwrap();
        match f.extension().and_then(|e| e.to_str()) {
            Some("png") => {
                assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "{}", f.display());
                let width = u32::from_be_bytes(bytes[16..20].try_into().unwrap());
                assert_eq!(width, 900, "{}", f.display());
                // Text is drawn (the built-in font): a blank PNG of this size compresses far
                // below this.
                assert!(
                    bytes.len() > 20_000,
                    "{}: {} bytes",
                    f.display(),
                    bytes.len()
                );
            }
            Some("svg") => {
                let text = String::from_utf8(bytes).unwrap();
                assert!(text.starts_with("<svg"), "{}", f.display());
                assert!(
                    text.contains("static-ideal"),
                    "{}: title missing",
                    f.display()
                );
            }
            other => panic!("unexpected file {other:?}"),
        }
    }
    let imu = std::fs::read_to_string(dir.join("run_imu.svg")).unwrap();
    assert!(imu.contains("gyro z: mean rate per bucket"));
    std::fs::remove_dir_all(&dir).unwrap();
}
