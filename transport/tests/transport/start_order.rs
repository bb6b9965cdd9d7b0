//! Start order: the Rust navigator started before the plant (the case in which the Python
//! client lost its connection to the publisher about once in 17 runs with iceoryx2 0.10,
//! docs/transport.md) is served every time: 24 process pairs, the navigator ahead by 0 to 49 ms,
//! each run delivering every sample once.

use std::time::Duration;

use crate::peer::{BATCH, Peer, SAMPLES, field, left, remove_counter};

const WAIT: Duration = Duration::from_secs(20);

#[test]
fn a_navigator_started_before_the_plant_is_served_every_time() {
    let (n, b) = (SAMPLES.to_string(), BATCH.to_string());
    for i in 0..24u64 {
        let s = format!("o{}x{i}", std::process::id());
        let mut nav = Peer::spawn("nav", &s, &["--timeout-s", "10"]);
        // Head starts spread over the navigator's own start-up (a few ms) and its polling.
        std::thread::sleep(Duration::from_millis(i * 7 % 50));
        let mut plant = Peer::spawn(
            "plant",
            &s,
            &["--samples", &n, "--batch", &b, "--timeout-s", "10"],
        );
        let r = nav.expect("RESULT", WAIT);
        assert_eq!(
            (
                field(&r, "samples"),
                field(&r, "first_tick"),
                field(&r, "duplicates")
            ),
            (SAMPLES, 0, 0),
            "run {i}: {r}"
        );
        let (p_ok, n_ok) = (plant.finish(WAIT), nav.finish(WAIT));
        assert!(p_ok && n_ok, "run {i}\n{}\n{}", plant.said(), nav.said());
        assert!(left(&s).is_empty(), "run {i} left {:?}", left(&s));
        remove_counter(&s);
    }
}
