//! Plant state by value: everything that evolves, as bytes, so a run can be saved and resumed
//! bit-identically in another process (FMU state serialisation, transport restarts).
//!
//! Layout: magic `RINSPS03`, a fingerprint of the configuration (the state only restores into
//! the plant it came from), then little-endian u64/f64 fields stage by stage: the clock, the
//! temperature field, the readout, the truth, the sensor errors (declared effects only), the
//! motion (commands, carrier). Each stage writes and reads its own part. Caches (dwell,
//! attitude, schedule cursor) are not saved: they are rebuilt and give the same bits.
//!
//! This module is the bottom of the saved state: the format's pieces every stage writes with.
//! The plant's own part (its header and the order of the stages) is `crate::plant::saved_state`,
//! so the stages and the plant import this file and it imports neither.

use nalgebra::Vector3;

use crate::config::PlantConfig;

/// The first bytes of every saved state (the version is its last two characters).
pub(crate) const MAGIC: &[u8; 8] = b"RINSPS03";

/// Why a state could not be restored.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum StateError {
    /// Not a plant state, or from another version.
    #[error("not a rins plant state (bad header)")]
    BadHeader,
    /// The state belongs to a plant with another configuration.
    #[error(
        "the state was saved from a plant with another configuration (fingerprint {saved:#018x}, this plant {current:#018x})"
    )]
    ConfigMismatch {
        /// Fingerprint in the state.
        saved: u64,
        /// Fingerprint of the configuration given.
        current: u64,
    },
    /// Truncated or trailing bytes.
    #[error("plant state has {got} bytes, expected {expected}")]
    Length {
        /// Bytes given.
        got: usize,
        /// Bytes expected.
        expected: usize,
    },
    /// The fields read do not make one plant (e.g. a seed's own isolation loop without the
    /// reference table's).
    #[error("plant state is inconsistent: {0}")]
    Inconsistent(String),
    /// The configuration itself is invalid.
    #[error("invalid configuration: {0}")]
    Config(String),
}

/// FNV-1a over the configuration's JSON form: equal configurations, equal fingerprints.
pub fn fingerprint(cfg: &PlantConfig) -> u64 {
    let text = serde_json::to_string(cfg).expect("PlantConfig serialises");
    text.bytes().fold(0xcbf2_9ce4_8422_2325u64, |h, b| {
        (h ^ b as u64).wrapping_mul(0x0100_0000_01b3)
    })
}

/// Appends fields to a byte buffer.
#[derive(Default)]
pub(crate) struct Writer(pub Vec<u8>);

impl Writer {
    pub fn u64(&mut self, v: u64) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }
    pub fn f64(&mut self, v: f64) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }
    pub fn v3(&mut self, v: &Vector3<f64>) {
        v.iter().for_each(|x| self.f64(*x));
    }
    pub fn u128(&mut self, v: u128) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }
}

/// Reads fields back in the same order.
pub(crate) struct Reader<'a> {
    bytes: &'a [u8],
    pos: usize,
}

impl<'a> Reader<'a> {
    /// Reads `bytes` from `pos` on.
    pub fn new(bytes: &'a [u8], pos: usize) -> Self {
        Self { bytes, pos }
    }

    /// Bytes read so far (the header's included).
    pub fn pos(&self) -> usize {
        self.pos
    }

    fn take<const N: usize>(&mut self) -> Result<[u8; N], StateError> {
        let end = self.pos + N;
        let s = self.bytes.get(self.pos..end).ok_or(StateError::Length {
            got: self.bytes.len(),
            expected: end,
        })?;
        self.pos = end;
        Ok(s.try_into().expect("length checked"))
    }
    pub fn u64(&mut self) -> Result<u64, StateError> {
        Ok(u64::from_le_bytes(self.take::<8>()?))
    }
    pub fn f64(&mut self) -> Result<f64, StateError> {
        Ok(f64::from_le_bytes(self.take::<8>()?))
    }
    pub fn v3(&mut self) -> Result<Vector3<f64>, StateError> {
        Ok(Vector3::new(self.f64()?, self.f64()?, self.f64()?))
    }
    pub fn u128(&mut self) -> Result<u128, StateError> {
        Ok(u128::from_le_bytes(self.take::<16>()?))
    }
}
