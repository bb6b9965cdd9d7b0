//! The typed walk behind the parameter table: every configuration type visits its own scalars,
//! mutably, under their scenario-file key paths, in the order of its fields (the order serde
//! writes them, which FMU value references depend on). [`super::flatten`], [`super::set`] and
//! [`super::apply`] address the configuration through this walk alone, so an FMU's start does
//! not serialise the configuration.
//!
//! Plain tables use `param_fields!` (below), which destructures the whole struct: a field added to a
//! configuration type without a place here does not compile. Enumerations are written by hand,
//! with the names serde reads and writes (`rename_all`), tested against serde.

use crate::carrier::spec::{
    AfterEnd, CarrierKind, CarrierSpec, LegSpec, RaoSpec, SeaRealisation, SeaSpec, ShipRaoSpec,
    ShipSpec, SpectrumKind, TrajectorySpec,
};
use crate::config::{PlantConfig, SensorSpec, VehicleSpec};
use crate::earth::{EarthSpec, SiteSpec};
use crate::effects::accel::{AccelBiasSpec, AccelSpec, VrwSpec};
use crate::effects::custom::{Axis, CustomKind, CustomSpec};
use crate::effects::encoder::{
    EncoderOffsetSpec, EncoderQuantizationSpec, EncoderScaleSpec, EncoderSpec,
};
use crate::effects::gyro::{
    ArwSpec, DitherSpec, GSensitivitySpec, GaussMarkovSpec, GradientBiasSpec, GyroBiasSpec,
    GyroSpec, NavFieldSpec, PositionBiasSpec, RrwSpec, Transition,
};
use crate::effects::temp_sensor::{
    TempNoiseSpec, TempOffsetSpec, TempResolutionSpec, TempSensorSpec,
};
use crate::effects::{MisalignmentSpec, QuantizationSpec, ScaleFactorSpec, TempPolySpec};
use crate::table::{GimbalAxis, RotationStep, SchemeKind, SchemeSpec};
use crate::thermal::{ChamberSpec, ThermalSpec};

/// One place of the configuration a key path names.
pub enum Slot<'a> {
    /// A table or an array: it holds parameters but is none itself (setting it is an error).
    Group,
    /// A real number.
    Real(&'a mut f64),
    /// A whole number over the u64 range (`run.seed`).
    Integer(&'a mut u64),
    /// A whole number over the u32 range (`run.substeps`, `carrier.ship.sea.sea_state`,
    /// `carrier.ship.sea.components`); a value beyond it does not fit.
    Count(&'a mut u32),
    /// A switch.
    Bool(&'a mut bool),
    /// An enumeration, read and set by its scenario-file name.
    Enum(&'a mut dyn Choice),
    /// Free text (a declared effect's name, regressor and unit; the trajectory file): structure,
    /// settable by name but no row of the table.
    Text(&'a mut String),
}

/// An enumeration of the configuration, by the names a scenario file uses for it.
pub trait Choice {
    /// The current variant's name.
    fn name(&self) -> &'static str;
    /// Every name, in variant order (for the scenario keys of [`super::ENUMS`], that list).
    fn names(&self) -> &'static [&'static str];
    /// Sets the variant called `name`; false (and no change) if there is none.
    fn set_name(&mut self, name: &str) -> bool;
}

/// A configuration type that visits each of its scalars mutably under its key path.
pub trait ParamFields {
    /// Calls `f` with every place of `self` and its key path, depth first in field order:
    /// tables and arrays as [`Slot::Group`] before their contents (except the whole
    /// configuration, whose path is empty). On entry `path` holds `self`'s key path; it holds
    /// it again on return.
    fn visit_fields(&mut self, path: &mut String, f: &mut dyn FnMut(&str, Slot<'_>));
}

/// Appends the name of array element `i` to `path` (`dph` → `dph[2]`): the one spelling of an
/// element's key path, for the table, for setting and for FMU variable names.
pub fn push_element(path: &mut String, i: usize) {
    // The digits by hand: this runs for every array element of every walk.
    let mut digits = [0u8; 20];
    let mut start = digits.len();
    let mut rest = i;
    loop {
        start -= 1;
        digits[start] = b'0' + (rest % 10) as u8;
        rest /= 10;
        if rest == 0 {
            break;
        }
    }
    path.push('[');
    path.extend(digits[start..].iter().map(|&d| char::from(d)));
    path.push(']');
}

/// Visits `value` as the field `key` of the table at `path`.
fn field<T: ParamFields + ?Sized>(
    path: &mut String,
    key: &str,
    value: &mut T,
    f: &mut dyn FnMut(&str, Slot<'_>),
) {
    let n = path.len();
    if n > 0 {
        path.push('.');
    }
    path.push_str(key);
    value.visit_fields(path, f);
    path.truncate(n);
}

/// A table announces itself (the root, with an empty path, does not: it has no name to set).
fn group(path: &str, f: &mut dyn FnMut(&str, Slot<'_>)) {
    if !path.is_empty() {
        f(path, Slot::Group);
    }
}

impl ParamFields for f64 {
    fn visit_fields(&mut self, path: &mut String, f: &mut dyn FnMut(&str, Slot<'_>)) {
        f(path, Slot::Real(self));
    }
}

impl ParamFields for u64 {
    fn visit_fields(&mut self, path: &mut String, f: &mut dyn FnMut(&str, Slot<'_>)) {
        f(path, Slot::Integer(self));
    }
}

impl ParamFields for u32 {
    fn visit_fields(&mut self, path: &mut String, f: &mut dyn FnMut(&str, Slot<'_>)) {
        f(path, Slot::Count(self));
    }
}

impl ParamFields for bool {
    fn visit_fields(&mut self, path: &mut String, f: &mut dyn FnMut(&str, Slot<'_>)) {
        f(path, Slot::Bool(self));
    }
}

impl ParamFields for String {
    fn visit_fields(&mut self, path: &mut String, f: &mut dyn FnMut(&str, Slot<'_>)) {
        f(path, Slot::Text(self));
    }
}

impl<T: ParamFields> ParamFields for [T] {
    fn visit_fields(&mut self, path: &mut String, f: &mut dyn FnMut(&str, Slot<'_>)) {
        group(path, f);
        let n = path.len();
        for (i, v) in self.iter_mut().enumerate() {
            push_element(path, i);
            v.visit_fields(path, f);
            path.truncate(n);
        }
    }
}

impl<T: ParamFields, const N: usize> ParamFields for [T; N] {
    fn visit_fields(&mut self, path: &mut String, f: &mut dyn FnMut(&str, Slot<'_>)) {
        self.as_mut_slice().visit_fields(path, f);
    }
}

impl<T: ParamFields> ParamFields for Vec<T> {
    fn visit_fields(&mut self, path: &mut String, f: &mut dyn FnMut(&str, Slot<'_>)) {
        self.as_mut_slice().visit_fields(path, f);
    }
}

/// [`ParamFields`] for plain tables: the fields in declaration order (serde's order), each under
/// its own name. The pattern names every field, so a new field must be listed here.
macro_rules! param_fields {
    ($($ty:ty { $($field:ident),* $(,)? })*) => {$(
        impl ParamFields for $ty {
            fn visit_fields(&mut self, path: &mut String, f: &mut dyn FnMut(&str, Slot<'_>)) {
                group(path, f);
                let Self { $($field),* } = self;
                $(field(path, stringify!($field), $field, f);)*
            }
        }
    )*};
}

param_fields! {
    VehicleSpec { azimuth_deg, pitch_deg, roll_deg }
    SensorSpec { gyro, accel, encoder, temperature }
    SiteSpec { lat_deg, lon_deg, height_m }
    EarthSpec { rotation, gravity }
    ChamberSpec { temp_c, profile }
    ThermalSpec {
        enabled,
        step_s,
        chamber,
        start_steady,
        capacitance_j_per_k,
        power_w,
        g_board_housing_w_per_k,
        g_gyro_housing_w_per_k,
        g_accel_housing_w_per_k,
        g_housing_chamber_w_per_k,
        g_gyro_gyro_w_per_k,
        g_board_gyro_w_per_k,
        g_board_gyro_convection_w_per_k,
        board_to_block_dir_body,
    }
    RotationStep { axis, angle_deg, rate_dps, dwell_s }
    SchemeSpec {
        kind,
        rate_dps,
        accel_dps2,
        dwell_s,
        lead_dwell_s,
        axis,
        initial_outer_deg,
        initial_inner_deg,
        repeat,
        steps,
    }
    ScaleFactorSpec { enabled, ppm }
    MisalignmentSpec { enabled, arcsec }
    TempPolySpec { enabled, ref_temp_c, per_k, per_k2, per_k3 }
    QuantizationSpec { enabled, pulse }
    GyroBiasSpec { enabled, dph }
    PositionBiasSpec { enabled, dph, transition, ref_temp_c, dph_per_k, dph_per_k2, dph_per_k3 }
    GradientBiasSpec { enabled, dph_per_k }
    GSensitivitySpec { enabled, dph_per_g }
    DitherSpec { enabled, amplitude_change, dph_per_amplitude }
    NavFieldSpec { enabled, dph_enu }
    ArwSpec { enabled, dpsh }
    GaussMarkovSpec { enabled, sigma_dph, tau_s }
    RrwSpec { enabled, dph_per_sqrth }
    AccelBiasSpec { enabled, ug }
    VrwSpec { enabled, ug_per_sqrthz }
    EncoderScaleSpec { enabled, ppm }
    EncoderOffsetSpec { enabled, arcsec }
    EncoderQuantizationSpec { enabled, resolution_arcsec }
    EncoderSpec { scale_factor, offset, quantization }
    TempOffsetSpec { enabled, k }
    TempNoiseSpec { enabled, sigma_k }
    TempResolutionSpec { enabled, lsb_k }
    TempSensorSpec { offset, noise, resolution }
    CustomSpec { name, enabled, kind, regressor, unit, axes, coef }
    CarrierSpec { kind, lever_arm_m, ship, trajectory, azimuth_isolation }
    LegSpec { heading_deg, speed_kn, duration_s }
    RaoSpec { gain, natural_period_s, damping }
    ShipRaoSpec { roll, pitch, yaw, heave, surge, sway }
    SeaSpec {
        spectrum,
        sea_state,
        hs_m,
        tp_s,
        gamma,
        heading_to_waves_deg,
        components,
        band,
        rao,
        realisation,
        seed,
    }
    ShipSpec { lat_deg, lon_deg, height_m, legs, turn_rate_dps, accel_mps2, sea }
    TrajectorySpec { file, after_end }
}

/// The run's fields live in the file's `[run]` table.
impl ParamFields for PlantConfig {
    fn visit_fields(&mut self, path: &mut String, f: &mut dyn FnMut(&str, Slot<'_>)) {
        group(path, f);
        let Self {
            rate_hz,
            substeps,
            seed,
            site,
            vehicle,
            earth,
            scheme,
            sensor,
            thermal,
            carrier,
        } = self;
        field(path, "run.rate_hz", rate_hz, f);
        field(path, "run.substeps", substeps, f);
        field(path, "run.seed", seed, f);
        field(path, "site", site, f);
        field(path, "vehicle", vehicle, f);
        field(path, "earth", earth, f);
        field(path, "scheme", scheme, f);
        field(path, "sensor", sensor, f);
        field(path, "thermal", thermal, f);
        field(path, "carrier", carrier, f);
    }
}

/// Declared effects are written only when there are some (`skip_serializing_if`), so an empty
/// list is no key at all.
impl ParamFields for GyroSpec {
    fn visit_fields(&mut self, path: &mut String, f: &mut dyn FnMut(&str, Slot<'_>)) {
        group(path, f);
        let Self {
            bias,
            scale_factor,
            scale_factor_asymmetry,
            misalignment,
            temperature_bias,
            temperature_gradient_bias,
            g_sensitivity,
            position_bias,
            dither_bias,
            nav_field_bias,
            angle_random_walk,
            bias_instability,
            rate_random_walk,
            quantization,
            custom,
        } = self;
        field(path, "bias", bias, f);
        field(path, "scale_factor", scale_factor, f);
        field(path, "scale_factor_asymmetry", scale_factor_asymmetry, f);
        field(path, "misalignment", misalignment, f);
        field(path, "temperature_bias", temperature_bias, f);
        field(
            path,
            "temperature_gradient_bias",
            temperature_gradient_bias,
            f,
        );
        field(path, "g_sensitivity", g_sensitivity, f);
        field(path, "position_bias", position_bias, f);
        field(path, "dither_bias", dither_bias, f);
        field(path, "nav_field_bias", nav_field_bias, f);
        field(path, "angle_random_walk", angle_random_walk, f);
        field(path, "bias_instability", bias_instability, f);
        field(path, "rate_random_walk", rate_random_walk, f);
        field(path, "quantization", quantization, f);
        if !custom.is_empty() {
            field(path, "custom", custom, f);
        }
    }
}

/// Declared effects as for the gyros: an empty list is no key.
impl ParamFields for AccelSpec {
    fn visit_fields(&mut self, path: &mut String, f: &mut dyn FnMut(&str, Slot<'_>)) {
        group(path, f);
        let Self {
            bias,
            scale_factor,
            misalignment,
            temperature_bias,
            velocity_random_walk,
            quantization,
            custom,
        } = self;
        field(path, "bias", bias, f);
        field(path, "scale_factor", scale_factor, f);
        field(path, "misalignment", misalignment, f);
        field(path, "temperature_bias", temperature_bias, f);
        field(path, "velocity_random_walk", velocity_random_walk, f);
        field(path, "quantization", quantization, f);
        if !custom.is_empty() {
            field(path, "custom", custom, f);
        }
    }
}

/// The variant of `all` called `name`, set into `slot`.
fn pick<T: Choice + Copy>(slot: &mut T, name: &str, all: &[T]) -> bool {
    match all.iter().find(|v| v.name() == name) {
        Some(v) => {
            *slot = *v;
            true
        }
        None => false,
    }
}

/// The names of a scenario key of [`super::ENUMS`] (empty if the key were missing there, which
/// a test rules out).
fn listed(key: &str) -> &'static [&'static str] {
    super::ENUMS
        .iter()
        .find(|(k, _)| *k == key)
        .map_or(&[], |(_, c)| *c)
}

/// Every enumeration is a leaf of the walk.
macro_rules! enum_slot {
    ($($ty:ty),* $(,)?) => {$(
        impl ParamFields for $ty {
            fn visit_fields(&mut self, path: &mut String, f: &mut dyn FnMut(&str, Slot<'_>)) {
                f(path, Slot::Enum(self));
            }
        }
    )*};
}

enum_slot!(
    SchemeKind,
    GimbalAxis,
    Transition,
    CarrierKind,
    SpectrumKind,
    SeaRealisation,
    CustomKind,
    Axis,
    AfterEnd
);

impl Choice for SchemeKind {
    fn name(&self) -> &'static str {
        match self {
            Self::SixteenPosition => "sixteen-position",
            Self::EightPosition => "eight-position",
            Self::Continuous => "continuous",
            Self::Static => "static",
            Self::ZUpCalibration => "z-up-calibration",
            Self::ZDownCalibration => "z-down-calibration",
            Self::Steps => "steps",
        }
    }
    fn names(&self) -> &'static [&'static str] {
        listed("scheme.kind")
    }
    fn set_name(&mut self, name: &str) -> bool {
        pick(
            self,
            name,
            &[
                Self::SixteenPosition,
                Self::EightPosition,
                Self::Continuous,
                Self::Static,
                Self::ZUpCalibration,
                Self::ZDownCalibration,
                Self::Steps,
            ],
        )
    }
}

/// `scheme.axis` and each step's `axis`.
impl Choice for GimbalAxis {
    fn name(&self) -> &'static str {
        match self {
            Self::Outer => "outer",
            Self::Inner => "inner",
        }
    }
    fn names(&self) -> &'static [&'static str] {
        listed("scheme.axis")
    }
    fn set_name(&mut self, name: &str) -> bool {
        pick(self, name, &[Self::Outer, Self::Inner])
    }
}

impl Choice for Transition {
    fn name(&self) -> &'static str {
        match self {
            Self::Cosine => "cosine",
            Self::Step => "step",
        }
    }
    fn names(&self) -> &'static [&'static str] {
        listed("sensor.gyro.position_bias.transition")
    }
    fn set_name(&mut self, name: &str) -> bool {
        pick(self, name, &[Self::Cosine, Self::Step])
    }
}

impl Choice for CarrierKind {
    fn name(&self) -> &'static str {
        match self {
            Self::Static => "static",
            Self::Ship => "ship",
            Self::Trajectory => "trajectory",
        }
    }
    fn names(&self) -> &'static [&'static str] {
        listed("carrier.kind")
    }
    fn set_name(&mut self, name: &str) -> bool {
        pick(self, name, &[Self::Static, Self::Ship, Self::Trajectory])
    }
}

impl Choice for SpectrumKind {
    fn name(&self) -> &'static str {
        match self {
            Self::None => "none",
            Self::PiersonMoskowitz => "pierson-moskowitz",
            Self::Jonswap => "jonswap",
        }
    }
    fn names(&self) -> &'static [&'static str] {
        listed("carrier.ship.sea.spectrum")
    }
    fn set_name(&mut self, name: &str) -> bool {
        pick(
            self,
            name,
            &[Self::None, Self::PiersonMoskowitz, Self::Jonswap],
        )
    }
}

impl Choice for SeaRealisation {
    fn name(&self) -> &'static str {
        match self {
            Self::PerRun => "per-run",
            Self::Fixed => "fixed",
        }
    }
    fn names(&self) -> &'static [&'static str] {
        listed("carrier.ship.sea.realisation")
    }
    fn set_name(&mut self, name: &str) -> bool {
        pick(self, name, &[Self::PerRun, Self::Fixed])
    }
}

/// A declared effect's kind: structure, not in [`super::ENUMS`].
impl Choice for CustomKind {
    fn name(&self) -> &'static str {
        match self {
            Self::Bias => "bias",
            Self::ScaleFactor => "scale-factor",
        }
    }
    fn names(&self) -> &'static [&'static str] {
        &["bias", "scale-factor"]
    }
    fn set_name(&mut self, name: &str) -> bool {
        pick(self, name, &[Self::Bias, Self::ScaleFactor])
    }
}

/// A declared effect's axes: structure, not in [`super::ENUMS`].
impl Choice for Axis {
    fn name(&self) -> &'static str {
        match self {
            Self::X => "x",
            Self::Y => "y",
            Self::Z => "z",
        }
    }
    fn names(&self) -> &'static [&'static str] {
        &["x", "y", "z"]
    }
    fn set_name(&mut self, name: &str) -> bool {
        pick(self, name, &[Self::X, Self::Y, Self::Z])
    }
}

/// What a trajectory carrier does after the file's end: data, not in [`super::ENUMS`].
impl Choice for AfterEnd {
    fn name(&self) -> &'static str {
        match self {
            Self::Error => "error",
            Self::Hold => "hold",
        }
    }
    fn names(&self) -> &'static [&'static str] {
        &["error", "hold"]
    }
    fn set_name(&mut self, name: &str) -> bool {
        pick(self, name, &[Self::Error, Self::Hold])
    }
}
