//! The variable table of the carrier FMU: the ship's parameters (every `carrier.ship.*` key of
//! the plant's own parameter table, plus `run.seed` for the sea realisation and `run.rate_hz`
//! for the tick), then the carrier state as outputs ([`outputs`]).

use std::sync::OnceLock;

use nalgebra::{Rotation3, UnitQuaternion};
use rins_fmi::vars::{Kind, OutputDecl, Value, VariableTable};
use rins_fmi_plant::PlantParams;
use rins_plant::PlantConfig;
use rins_plant::carrier::{CarrierKind, CarrierState, SpectrumKind};

/// How an output reads element `i` of the carrier state.
pub type Read = fn(&CarrierState, usize) -> f64;

/// One output row: its declaration and how it reads the state.
pub struct Output {
    /// Name, length, unit, description.
    pub decl: OutputDecl,
    /// Reader.
    pub read: Read,
}

/// Whether scenario key `path` is a parameter of the carrier FMU.
pub fn is_carrier_param(path: &str) -> bool {
    path.starts_with("carrier.ship.") || path == "run.seed" || path == "run.rate_hz"
}

/// The attitude q_c^n (w, x, y, z) of `s`, with w ≥ 0 (q and −q are one attitude; a fixed
/// hemisphere keeps the output a function of the state).
pub fn q_cn(s: &CarrierState) -> [f64; 4] {
    let q = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(s.c_cn));
    let c = if q.w < 0.0 { -q.coords } else { q.coords };
    [c.w, c.x, c.y, c.z]
}

fn output(
    name: &str,
    len: Option<usize>,
    unit: &'static str,
    description: &str,
    read: Read,
) -> Output {
    Output {
        decl: OutputDecl {
            name: name.into(),
            len,
            kind: Kind::Real,
            unit: (unit != "1").then_some(unit),
            start: vec![Value::Real(0.0)],
            description: description.into(),
        },
        read,
    }
}

/// The outputs: what a vessel model gives, the names the IMU FMU's carrier inputs carry.
pub fn outputs() -> &'static [Output] {
    static OUT: OnceLock<Vec<Output>> = OnceLock::new();
    OUT.get_or_init(|| {
        vec![
            output("carrier.lat_deg", None, "deg", "geodetic latitude of the carrier reference point (WGS-84)", |s, _| s.lat_rad.to_degrees()),
            output("carrier.lon_deg", None, "deg", "longitude of the carrier reference point", |s, _| s.lon_rad.to_degrees()),
            output("carrier.height_m", None, "m", "ellipsoidal height of the carrier reference point", |s, _| s.height_m),
            output("carrier.v_enu_mps", Some(3), "m/s", "ground velocity of the reference point, east, north, up", |s, i| s.v_n[i]),
            output("carrier.q_cn", Some(4), "1", "attitude quaternion q_c^n (w, x, y, z; w >= 0): carrier axes (x starboard, y bow, z up) to east-north-up", |s, i| q_cn(s)[i]),
            output("carrier.omega_nc_c_rps", Some(3), "rad/s", "angular rate of the carrier relative to east-north-up, carrier axes", |s, i| s.omega_nc_c[i]),
            output("carrier.a_enu_mps2", Some(3), "m/s2", "acceleration of the reference point (time derivative of the ENU velocity)", |s, i| s.a_n[i]),
        ]
    })
}

/// What a slot is.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Role {
    /// A scenario parameter, by key path.
    Param(String),
    /// Element `.1` of output row `.0`.
    Output(usize, usize),
}

pub(crate) struct Table {
    pub vars: VariableTable,
    pub roles: Vec<Role>,
    /// The ship's parameters (the first slots) and the configuration they describe.
    pub params: PlantParams,
}

/// The defaults: the plant's ship (12 kn due north from 36.6° N 123.6° E) in a
/// Pierson–Moskowitz sea state 5, so the FMU moves like a ship out of the box.
pub fn defaults() -> PlantConfig {
    let mut cfg = rins_plant::presets::paper_16pos_config();
    cfg.carrier.kind = CarrierKind::Ship;
    cfg.carrier.ship.sea.spectrum = SpectrumKind::PiersonMoskowitz;
    cfg.carrier.ship.sea.sea_state = 5;
    cfg
}

fn build_table() -> Table {
    let mut scalars = Vec::new();
    let params = PlantParams::push_vars(defaults(), is_carrier_param, &mut scalars);
    let mut roles: Vec<Role> = params.iter().map(|(_, p)| Role::Param(p.into())).collect();
    for (k, o) in outputs().iter().enumerate() {
        for (e, v) in o.decl.scalars().enumerate() {
            scalars.push(v);
            roles.push(Role::Output(k, e));
        }
    }
    let mut vars = VariableTable::with_enum_codes(scalars);
    // Every initial output depends on the ship's parameters (start point, first leg, sea):
    // all of them and the enumeration codes, a superset the FMI standards allow.
    let mut knowns: Vec<usize> = params.slots.clone().collect();
    knowns.extend(vars.enum_codes.iter().map(|(code, _)| *code));
    for (slot, r) in roles.iter().enumerate() {
        if matches!(r, Role::Output(..)) {
            vars.initial_dependencies[slot] = knowns.clone();
        }
    }
    Table {
        vars,
        roles,
        params,
    }
}

/// The table (built once from constants).
pub(crate) fn table() -> &'static Table {
    static TABLE: OnceLock<Table> = OnceLock::new();
    TABLE.get_or_init(build_table)
}
