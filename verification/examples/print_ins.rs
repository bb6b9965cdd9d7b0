//! Development aid: prints the closed-form INS cases.
use rins_verify::ins::*;
fn main() {
    let t = std::time::Instant::now();
    for axis in 0..0 {
        println!("{:?}", gyro_bias_case(axis, 0.01, 168.0, 20.0));
    }
    println!("{:?}", accel_bias_case(50.0, 30.0, 20.0));
    println!("{:?}", arw_case(0.003, 2, 1.0, 10.0));
    println!("wall {:.1} s", t.elapsed().as_secs_f64());
}
