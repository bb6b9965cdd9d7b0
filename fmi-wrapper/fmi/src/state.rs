//! The FMU state codec: little-endian fixed-width fields in a fixed order, by value (no
//! pointers), so a state serialised in one process restores in another. The instance header and
//! every model's own fields go through it; a model may append an opaque block of its own
//! (the rins plant appends its state in the plant's codec).

use crate::vars::{Value, VariableTable};

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

    /// The value of every slot of a model's table, count first ([`StateReader::values`]).
    pub fn values(&mut self, values: &[Value]) {
        self.u64(values.len() as u64);
        values.iter().for_each(|v| self.value(*v));
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

    /// The value of every slot of `table`, as [`StateWriter::values`] wrote them. A state of
    /// another table (another count) or a value of the wrong kind, out of range or past an
    /// enumeration's items (a corrupted state) is an error naming the slot.
    pub fn values(&mut self, table: &VariableTable) -> Result<Vec<Value>, String> {
        let n = self.u64()?;
        let expected = table.scalars.len();
        if n != expected as u64 {
            return Err(format!("state has {n} variables, this FMU has {expected}"));
        }
        let values: Vec<Value> = (0..n).map(|_| self.value()).collect::<Result<_, _>>()?;
        for (slot, v) in values.iter().enumerate() {
            table
                .check(slot, *v)
                .map_err(|e| format!("variable {slot}: {e}"))?;
        }
        Ok(values)
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

    #[test]
    fn a_table_s_values_round_trip_and_a_foreign_or_bad_one_is_refused() {
        use crate::vars::{Causality, Kind, ScalarVar};
        let var = |name: &str| ScalarVar {
            name: name.into(),
            array: name.into(),
            kind: Kind::Real,
            causality: Causality::Parameter,
            unit: None,
            start: Value::Real(0.0),
            range: Some((0.0, 1.0)),
            description: String::new(),
        };
        let table = VariableTable::new(vec![var("a"), var("b")]);
        let mut w = StateWriter::default();
        w.values(&[Value::Real(0.5), Value::Real(1.0)]);
        assert_eq!(
            StateReader::new(&w.0).values(&table).unwrap(),
            [Value::Real(0.5), Value::Real(1.0)]
        );
        let mut short = StateWriter::default();
        short.values(&[Value::Real(0.5)]);
        assert_eq!(
            StateReader::new(&short.0).values(&table).unwrap_err(),
            "state has 1 variables, this FMU has 2"
        );
        let mut bad = StateWriter::default();
        bad.values(&[Value::Real(0.5), Value::Real(2.0)]);
        let e = StateReader::new(&bad.0).values(&table).unwrap_err();
        assert!(e.starts_with("variable 1: b = 2 is outside"), "{e}");
    }
}
