//! Profiling aid: the ideal plant on a static table.
fn main() {
    let mut c = rins_plant::PlantConfig::default();
    c.scheme.kind = rins_plant::table::SchemeKind::Static;
    let mut p = rins_plant::Plant::new(&c).unwrap();
    let mut acc = 0.0;
    for _ in 0..20_000_000u64 {
        acc += p.step().dtheta_rad.z;
    }
    println!("{acc}");
}
