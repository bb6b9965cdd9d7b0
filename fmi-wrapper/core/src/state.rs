//! The FMU state codec: little-endian fixed-width fields in a fixed order, by value (no
//! pointers), so a state serialised in one process restores in another. The instance header and
//! every model's own fields go through it; a model may append an opaque block of its own
//! (the rins plant appends its state in the plant's codec).

use crate::vars::Value;

/// Appends fields to a byte buffer.
#[derive(Clone, Debug, Default)]
pub struct StateWriter(pub Vec<u8>);

impl StateWriter {
    /// A whole number.
    pub fn u64(&mut self, v: u64) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }

    /// A float, bit for bit.
    pub fn f64(&mut self, v: f64) {
        self.u64(v.to_bits());
    }

    /// A variable value: kind tag, then its bits.
    pub fn value(&mut self, v: Value) {
        let (tag, bits) = match v {
            Value::Real(x) => (0, x.to_bits()),
            Value::Integer(u) => (1, u),
            Value::Boolean(b) => (2, b as u64),
            Value::Enumeration(i) => (3, i as u64),
        };
        self.u64(tag);
        self.u64(bits);
    }

    /// A length-prefixed block of bytes.
    pub fn bytes(&mut self, b: &[u8]) {
        self.u64(b.len() as u64);
        self.0.extend_from_slice(b);
    }
}

/// Reads fields back in the order they were written; running past the end is an error.
#[derive(Clone, Debug)]
pub struct StateReader<'a> {
    bytes: &'a [u8],
    pos: usize,
}

impl<'a> StateReader<'a> {
    /// A reader at the start of `bytes`.
    pub fn new(bytes: &'a [u8]) -> Self {
        Self { bytes, pos: 0 }
    }

    fn take(&mut self, n: usize) -> Result<&'a [u8], String> {
        let b = self
            .bytes
            .get(self.pos..self.pos.saturating_add(n))
            .ok_or_else(|| {
                format!(
                    "truncated state: {} bytes, needed {} more at offset {}",
                    self.bytes.len(),
                    n,
                    self.pos
                )
            })?;
        self.pos += n;
        Ok(b)
    }

    /// A whole number.
    pub fn u64(&mut self) -> Result<u64, String> {
        Ok(u64::from_le_bytes(
            self.take(8)?.try_into().expect("8 bytes"),
        ))
    }

    /// A float.
    pub fn f64(&mut self) -> Result<f64, String> {
        Ok(f64::from_bits(self.u64()?))
    }

    /// A variable value.
    pub fn value(&mut self) -> Result<Value, String> {
        let (tag, bits) = (self.u64()?, self.u64()?);
        Ok(match tag {
            0 => Value::Real(f64::from_bits(bits)),
            1 => Value::Integer(bits),
            2 => Value::Boolean(bits != 0),
            3 => Value::Enumeration(bits as usize),
            _ => return Err(format!("unknown value tag {tag}")),
        })
    }

    /// A length-prefixed block of bytes.
    pub fn bytes(&mut self) -> Result<&'a [u8], String> {
        let n = usize::try_from(self.u64()?).map_err(|_| "block length overflows")?;
        self.take(n)
    }

    /// Fails unless every byte was read (trailing bytes mean another layout).
    pub fn finish(&self) -> Result<(), String> {
        if self.pos == self.bytes.len() {
            Ok(())
        } else {
            Err(format!(
                "state has {} bytes, the layout read {}",
                self.bytes.len(),
                self.pos
            ))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fields_round_trip_and_truncation_is_reported() {
        let mut w = StateWriter::default();
        w.u64(7);
        w.f64(-0.0);
        w.value(Value::Enumeration(2));
        w.value(Value::Real(f64::INFINITY));
        w.bytes(b"abc");
        let mut r = StateReader::new(&w.0);
        assert_eq!(r.u64().unwrap(), 7);
        assert_eq!(r.f64().unwrap().to_bits(), (-0.0f64).to_bits());
        assert_eq!(r.value().unwrap(), Value::Enumeration(2));
        assert_eq!(r.value().unwrap(), Value::Real(f64::INFINITY));
        assert_eq!(r.bytes().unwrap(), b"abc");
        r.finish().unwrap();
        let mut short = StateReader::new(&w.0[..12]);
        short.u64().unwrap();
        assert!(short.u64().unwrap_err().contains("truncated"));
    }
}
