//! Lumped thermal network of the IMU: electronics board, three RLG blocks, accelerometer
//! cluster and housing, driven by the chamber (ambient) temperature and internal heat sources.
//!
//! Board-to-gyro convection depends on the gravity direction in the body frame: heat rises, so
//! the coupling is strongest when the board sits below the mono block (the paper's "heat
//! transfer by gravity from the electric board to the mono block", Section 4.1).

use nalgebra::{Matrix6, Vector3, Vector6};
use serde::{Deserialize, Serialize};

/// Node indices of the network.
pub mod node {
    /// Electronics board.
    pub const BOARD: usize = 0;
    /// RLG block sensing body x (y, z follow).
    pub const GYRO_X: usize = 1;
    /// Accelerometer cluster.
    pub const ACCEL: usize = 4;
    /// Housing (the only node coupled to the chamber).
    pub const HOUSING: usize = 5;
    /// Number of nodes.
    pub const COUNT: usize = 6;
    /// Node names in index order, as used in output columns.
    pub const NAMES: [&str; COUNT] = ["board", "gyro_x", "gyro_y", "gyro_z", "accel", "housing"];
}

/// Lowest chamber temperature the network parameters are meant for, °C.
pub const CHAMBER_MIN_C: f64 = -55.0;
/// Highest chamber temperature the network parameters are meant for, °C.
pub const CHAMBER_MAX_C: f64 = 125.0;

/// Chamber (ambient) temperature: a constant, or a piecewise-linear profile held at its ends.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ChamberSpec {
    /// Constant chamber temperature, °C (used when `profile` is empty).
    pub temp_c: f64,
    /// Breakpoints `[t_s, temp_c]`, strictly increasing in time.
    pub profile: Vec<[f64; 2]>,
}

impl Default for ChamberSpec {
    fn default() -> Self {
        Self {
            temp_c: 25.0,
            profile: Vec::new(),
        }
    }
}

impl ChamberSpec {
    /// Chamber temperature at `t_s`, °C.
    pub fn temp_at(&self, t_s: f64) -> f64 {
        let p = &self.profile;
        if p.is_empty() {
            return self.temp_c;
        }
        let i = p.partition_point(|q| q[0] <= t_s);
        if i == 0 {
            return p[0][1];
        }
        if i == p.len() {
            return p[p.len() - 1][1];
        }
        let (a, b) = (p[i - 1], p[i]);
        a[1] + (b[1] - a[1]) * (t_s - a[0]) / (b[0] - a[0])
    }
}

/// Parameters of the thermal network.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ThermalSpec {
    /// When off, every node follows the chamber temperature instantly (no self-heating).
    pub enabled: bool,
    /// Update interval, s; a whole multiple of the output interval. Backward Euler: stable at any step.
    pub step_s: f64,
    /// Chamber temperature.
    pub chamber: ChamberSpec,
    /// Start from the steady state at the initial chamber temperature and attitude (true), or
    /// with every node at the initial chamber temperature (false, a cold start).
    pub start_steady: bool,
    /// Heat capacities of board, gyro x/y/z, accelerometers, housing, J/K.
    pub capacitance_j_per_k: [f64; 6],
    /// Internal heat sources of the same nodes, W.
    pub power_w: [f64; 6],
    /// Board–housing conductance, W/K.
    pub g_board_housing_w_per_k: f64,
    /// Gyro block–housing conductances, W/K.
    pub g_gyro_housing_w_per_k: [f64; 3],
    /// Accelerometer cluster–housing conductance, W/K.
    pub g_accel_housing_w_per_k: f64,
    /// Housing–chamber conductance, W/K.
    pub g_housing_chamber_w_per_k: f64,
    /// Conduction between neighbouring gyro blocks (mono block), W/K.
    pub g_gyro_gyro_w_per_k: f64,
    /// Board–gyro conduction, W/K.
    pub g_board_gyro_w_per_k: [f64; 3],
    /// Extra board–gyro convective conductance when the gyro block is straight above the board,
    /// W/K; scaled by (1 + d·u)/2 with d the board→block direction and u the body up direction.
    pub g_board_gyro_convection_w_per_k: [f64; 3],
    /// Direction from the board to the mono block in body axes (normalised internally).
    pub board_to_block_dir_body: [f64; 3],
}

impl Default for ThermalSpec {
    /// Order-of-magnitude values for a navigation-grade RLG IMU: Zerodur blocks of ~0.5 kg
    /// (c ≈ 800 J/kg/K) dissipating ~1.4 W each (Li et al., Sensors 15:29910), a 10 W board,
    /// a housing time constant of about half an hour.
    fn default() -> Self {
        Self {
            enabled: true,
            step_s: 1.0,
            chamber: ChamberSpec::default(),
            start_steady: true,
            capacitance_j_per_k: [200.0, 400.0, 400.0, 400.0, 100.0, 5000.0],
            power_w: [10.0, 1.4, 1.4, 1.4, 1.0, 0.0],
            g_board_housing_w_per_k: 0.5,
            g_gyro_housing_w_per_k: [0.3, 0.3, 0.3],
            g_accel_housing_w_per_k: 0.2,
            g_housing_chamber_w_per_k: 3.0,
            g_gyro_gyro_w_per_k: 0.5,
            g_board_gyro_w_per_k: [0.1, 0.1, 0.1],
            g_board_gyro_convection_w_per_k: [0.05, 0.05, 0.05],
            board_to_block_dir_body: [0.0, 0.0, 1.0],
        }
    }
}

/// Node temperatures and the derived quantities the sensor effects use.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Temperatures {
    /// Node temperatures, °C, indexed by [`node`].
    pub nodes_c: [f64; node::COUNT],
    /// Chamber temperature, °C.
    pub chamber_c: f64,
}

impl Temperatures {
    /// Temperature of each gyro block, °C.
    pub fn gyro_c(&self) -> Vector3<f64> {
        Vector3::new(self.nodes_c[1], self.nodes_c[2], self.nodes_c[3])
    }
    /// Gradient across each gyro block, taken as block minus housing, K.
    pub fn gyro_gradient_k(&self) -> Vector3<f64> {
        let h = self.nodes_c[node::HOUSING];
        Vector3::new(
            self.nodes_c[1] - h,
            self.nodes_c[2] - h,
            self.nodes_c[3] - h,
        )
    }
    /// Accelerometer cluster temperature, °C.
    pub fn accel_c(&self) -> f64 {
        self.nodes_c[node::ACCEL]
    }
}

/// The network and its state.
#[derive(Clone, Debug)]
pub struct ThermalNetwork {
    spec: ThermalSpec,
    dir: Vector3<f64>,
    temps: Vector6<f64>,
    chamber_c: f64,
    cached_up_dot: f64,
    cached_step_s: f64,
    cached_lu: Option<nalgebra::LU<f64, nalgebra::U6, nalgebra::U6>>,
}

impl ThermalNetwork {
    /// Builds the network at chamber temperature `chamber_c` with the body up direction `up_b`.
    pub fn new(spec: &ThermalSpec, chamber_c: f64, up_b: &Vector3<f64>) -> Self {
        let d = Vector3::from(spec.board_to_block_dir_body);
        let dir = if d.norm() > 0.0 { d.normalize() } else { d };
        let mut net = Self {
            spec: spec.clone(),
            dir,
            temps: Vector6::repeat(chamber_c),
            chamber_c,
            cached_up_dot: f64::NAN,
            cached_step_s: f64::NAN,
            cached_lu: None,
        };
        if spec.enabled && spec.start_steady {
            net.temps = net.steady_state(chamber_c, up_b);
        }
        net
    }

    /// Current temperatures.
    pub fn temperatures(&self) -> Temperatures {
        Temperatures {
            nodes_c: self.temps.into(),
            chamber_c: self.chamber_c,
        }
    }

    /// Overwrites the state (used by state restore).
    pub fn set_state(&mut self, nodes_c: [f64; 6], chamber_c: f64) {
        self.temps = Vector6::from(nodes_c);
        self.chamber_c = chamber_c;
    }

    /// Conductance matrix L (graph Laplacian plus the chamber link on the housing diagonal)
    /// for a body up direction whose projection on the board→block direction is `up_dot`.
    pub fn conductance_matrix(&self, up_dot: f64) -> Matrix6<f64> {
        let s = &self.spec;
        let mut l = Matrix6::zeros();
        let mut link = |i: usize, j: usize, g: f64| {
            l[(i, i)] += g;
            l[(j, j)] += g;
            l[(i, j)] -= g;
            l[(j, i)] -= g;
        };
        let rise = 0.5 * (1.0 + up_dot);
        link(node::BOARD, node::HOUSING, s.g_board_housing_w_per_k);
        link(node::ACCEL, node::HOUSING, s.g_accel_housing_w_per_k);
        for k in 0..3 {
            let gyro = node::GYRO_X + k;
            link(gyro, node::HOUSING, s.g_gyro_housing_w_per_k[k]);
            link(
                node::BOARD,
                gyro,
                s.g_board_gyro_w_per_k[k] + rise * s.g_board_gyro_convection_w_per_k[k],
            );
            link(gyro, node::GYRO_X + (k + 1) % 3, s.g_gyro_gyro_w_per_k);
        }
        l[(node::HOUSING, node::HOUSING)] += s.g_housing_chamber_w_per_k;
        l
    }

    fn source(&self, chamber_c: f64) -> Vector6<f64> {
        let mut p = Vector6::from(self.spec.power_w);
        p[node::HOUSING] += self.spec.g_housing_chamber_w_per_k * chamber_c;
        p
    }

    /// Steady state L·T = P + G_hc·T_chamber.
    pub fn steady_state(&self, chamber_c: f64, up_b: &Vector3<f64>) -> Vector6<f64> {
        let l = self.conductance_matrix(self.dir.dot(up_b));
        l.lu()
            .solve(&self.source(chamber_c))
            .unwrap_or_else(|| Vector6::repeat(chamber_c))
    }

    /// The chamber temperature changes with no time passing: the nodes keep their
    /// temperatures (their heat capacity), unless the network is off and they follow it.
    pub fn hold_chamber(&mut self, chamber_c: f64) {
        self.chamber_c = chamber_c;
        if !self.spec.enabled {
            self.temps = Vector6::repeat(chamber_c);
        }
    }

    /// Advances the network by `h_s` to a chamber temperature `chamber_c` with body up
    /// direction `up_b`: backward Euler, (C/h + L)·T⁺ = C/h·T + P + G_hc·T_ch. A-stable and
    /// L-stable, so any step is stable; accuracy is O(h/τ) on the fastest node.
    pub fn step(&mut self, h_s: f64, chamber_c: f64, up_b: &Vector3<f64>) {
        self.chamber_c = chamber_c;
        if !self.spec.enabled {
            self.temps = Vector6::repeat(chamber_c);
            return;
        }
        let up_dot = self.dir.dot(up_b);
        let cap = Vector6::from(self.spec.capacitance_j_per_k) / h_s;
        // Refactor only when the attitude-dependent convection or the step changed (dwells reuse it).
        if self.cached_lu.is_none()
            || (up_dot - self.cached_up_dot).abs() > 1e-12
            || h_s != self.cached_step_s
        {
            let a = self.conductance_matrix(up_dot) + Matrix6::from_diagonal(&cap);
            self.cached_lu = Some(a.lu());
            self.cached_up_dot = up_dot;
            self.cached_step_s = h_s;
        }
        let rhs = cap.component_mul(&self.temps) + self.source(chamber_c);
        if let Some(t) = self.cached_lu.as_ref().and_then(|lu| lu.solve(&rhs)) {
            self.temps = t;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn one_node_spec() -> ThermalSpec {
        // Housing only: decouple every internal node so the housing is a single RC node.
        ThermalSpec {
            power_w: [0.0; 6],
            g_board_housing_w_per_k: 0.0,
            g_gyro_housing_w_per_k: [0.0; 3],
            g_accel_housing_w_per_k: 0.0,
            g_gyro_gyro_w_per_k: 0.0,
            g_board_gyro_w_per_k: [0.0; 3],
            g_board_gyro_convection_w_per_k: [0.0; 3],
            ..ThermalSpec::default()
        }
    }

    #[test]
    fn housing_follows_first_order_step_response() {
        let spec = one_node_spec();
        let up = Vector3::z();
        let mut net = ThermalNetwork::new(&spec, 20.0, &up);
        let tau = spec.capacitance_j_per_k[5] / spec.g_housing_chamber_w_per_k;
        let h = 0.5;
        let n = (tau / h) as usize; // one time constant
        for _ in 0..n {
            net.step(h, 30.0, &up);
        }
        let t = net.temperatures().nodes_c[node::HOUSING];
        let exact = 30.0 - 10.0 * (-(n as f64) * h / tau).exp();
        // Backward Euler error is O(h/tau) of the swing.
        assert_relative_eq!(t, exact, epsilon = 10.0 * h / tau);
    }

    #[test]
    fn huge_steps_stay_bounded_and_reach_steady_state() {
        let spec = ThermalSpec::default();
        let up = Vector3::z();
        let mut net = ThermalNetwork::new(&spec, 0.0, &up);
        for _ in 0..50 {
            net.step(1e6, 40.0, &up);
            assert!(
                net.temperatures()
                    .nodes_c
                    .iter()
                    .all(|t| (0.0..200.0).contains(t))
            );
        }
        let ss = net.steady_state(40.0, &up);
        for i in 0..6 {
            assert_relative_eq!(net.temperatures().nodes_c[i], ss[i], epsilon = 1e-6);
        }
        // Energy balance at steady state: everything dissipated leaves through the housing link.
        let total: f64 = spec.power_w.iter().sum();
        assert_relative_eq!(
            spec.g_housing_chamber_w_per_k * (ss[node::HOUSING] - 40.0),
            total,
            epsilon = 1e-9
        );
    }

    #[test]
    fn heat_rises_gyro_blocks_warmer_when_board_is_below() {
        let spec = ThermalSpec::default();
        let up = ThermalNetwork::new(&spec, 25.0, &Vector3::z()).temperatures();
        let down = ThermalNetwork::new(&spec, 25.0, &(-Vector3::z())).temperatures();
        // Board below block (Z up): stronger coupling, so the block is warmer and the board cooler.
        assert!(up.nodes_c[node::GYRO_X] > down.nodes_c[node::GYRO_X]);
        assert!(up.nodes_c[node::BOARD] < down.nodes_c[node::BOARD]);
    }

    #[test]
    fn chamber_profile_interpolates_and_holds() {
        let c = ChamberSpec {
            temp_c: 0.0,
            profile: vec![[0.0, 10.0], [100.0, 20.0]],
        };
        assert_relative_eq!(c.temp_at(-5.0), 10.0);
        assert_relative_eq!(c.temp_at(25.0), 12.5);
        assert_relative_eq!(c.temp_at(1e9), 20.0);
    }
}
