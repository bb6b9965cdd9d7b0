//! The measurement format: the plant's own CSV is a valid measurement file (the reader and
//! its tests on bad files are in rins-mvm, mvm/tests/mvm/reader.rs).

use rins_mvm::csv::parse;
use rins_scenario::file::{OutputSpec, Scenario};
use rins_scenarios::sinks::CsvSink;
use rins_scenarios::{Sink, run};

#[test]
fn the_plants_own_csv_is_a_measurement_file() {
    let mut sc = Scenario::load(std::path::Path::new("builtin:paper-16pos-short")).unwrap();
    sc.meta.duration_s = 400.0;
    let opts = OutputSpec {
        decimation: 10,
        truth: true,
        effects: true,
        ..OutputSpec::default()
    };
    let mut sink = CsvSink::new(Vec::new(), opts, &sc.plant).unwrap();
    {
        let mut sinks: [&mut dyn Sink; 1] = [&mut sink];
        run(&sc, sc.samples(), &mut sinks).unwrap();
    }
    let text = String::from_utf8(sink.into_inner()).unwrap();
    let m = parse(&text, "plant.csv").unwrap();
    assert_eq!(m.rows, 4000);
    assert_eq!(m.temperature_columns().len(), 7);
    assert!(m.col("gyro_position_bias_z_dph").is_some());
}
