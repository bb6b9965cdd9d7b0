//! A deserializer adapter that refuses an array longer than the type reads. toml's spanned
//! document reader hands a fixed-size array (`[f64; 3]`) its first elements and drops the rest
//! without a word, where the `toml::Value` reader the scenario path used before refused them
//! ("invalid length 4, expected fewer elements in array"). Wrapped in [`WholeArrays`], every
//! sequence of the document must be read to its end; the error carries the array's span, so it
//! names the line and column.

use std::fmt;

use serde::de::{
    DeserializeSeed, Deserializer, EnumAccess, Error as _, IgnoredAny, MapAccess, SeqAccess,
    VariantAccess, Visitor,
};

/// Wraps a deserializer (or a visitor, a seed, an access) so that sequences are read whole.
pub(super) struct WholeArrays<T>(pub(super) T);

macro_rules! forward_deserialize {
    ($($method:ident)*) => {
        $(
            fn $method<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, D::Error> {
                self.0.$method(WholeArrays(visitor))
            }
        )*
    };
}

impl<'de, D: Deserializer<'de>> Deserializer<'de> for WholeArrays<D> {
    type Error = D::Error;

    forward_deserialize! {
        deserialize_any deserialize_bool deserialize_i8 deserialize_i16 deserialize_i32
        deserialize_i64 deserialize_i128 deserialize_u8 deserialize_u16 deserialize_u32
        deserialize_u64 deserialize_u128 deserialize_f32 deserialize_f64 deserialize_char
        deserialize_str deserialize_string deserialize_bytes deserialize_byte_buf
        deserialize_option deserialize_unit deserialize_seq deserialize_map
        deserialize_identifier deserialize_ignored_any
    }

    fn deserialize_unit_struct<V: Visitor<'de>>(
        self,
        name: &'static str,
        visitor: V,
    ) -> Result<V::Value, D::Error> {
        self.0.deserialize_unit_struct(name, WholeArrays(visitor))
    }

    fn deserialize_newtype_struct<V: Visitor<'de>>(
        self,
        name: &'static str,
        visitor: V,
    ) -> Result<V::Value, D::Error> {
        self.0
            .deserialize_newtype_struct(name, WholeArrays(visitor))
    }

    fn deserialize_tuple<V: Visitor<'de>>(
        self,
        len: usize,
        visitor: V,
    ) -> Result<V::Value, D::Error> {
        self.0.deserialize_tuple(len, WholeArrays(visitor))
    }

    fn deserialize_tuple_struct<V: Visitor<'de>>(
        self,
        name: &'static str,
        len: usize,
        visitor: V,
    ) -> Result<V::Value, D::Error> {
        self.0
            .deserialize_tuple_struct(name, len, WholeArrays(visitor))
    }

    fn deserialize_struct<V: Visitor<'de>>(
        self,
        name: &'static str,
        fields: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, D::Error> {
        self.0
            .deserialize_struct(name, fields, WholeArrays(visitor))
    }

    fn deserialize_enum<V: Visitor<'de>>(
        self,
        name: &'static str,
        variants: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, D::Error> {
        self.0
            .deserialize_enum(name, variants, WholeArrays(visitor))
    }
}

macro_rules! forward_visit {
    ($($method:ident($ty:ty))*) => {
        $(
            fn $method<E: serde::de::Error>(self, v: $ty) -> Result<V::Value, E> {
                self.0.$method(v)
            }
        )*
    };
}

impl<'de, V: Visitor<'de>> Visitor<'de> for WholeArrays<V> {
    type Value = V::Value;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.0.expecting(f)
    }

    forward_visit! {
        visit_bool(bool) visit_i8(i8) visit_i16(i16) visit_i32(i32) visit_i64(i64)
        visit_i128(i128) visit_u8(u8) visit_u16(u16) visit_u32(u32) visit_u64(u64)
        visit_u128(u128) visit_f32(f32) visit_f64(f64) visit_char(char) visit_str(&str)
        visit_borrowed_str(&'de str) visit_string(String) visit_bytes(&[u8])
        visit_borrowed_bytes(&'de [u8]) visit_byte_buf(Vec<u8>)
    }

    fn visit_none<E: serde::de::Error>(self) -> Result<V::Value, E> {
        self.0.visit_none()
    }

    fn visit_unit<E: serde::de::Error>(self) -> Result<V::Value, E> {
        self.0.visit_unit()
    }

    fn visit_some<D: Deserializer<'de>>(self, d: D) -> Result<V::Value, D::Error> {
        self.0.visit_some(WholeArrays(d))
    }

    fn visit_newtype_struct<D: Deserializer<'de>>(self, d: D) -> Result<V::Value, D::Error> {
        self.0.visit_newtype_struct(WholeArrays(d))
    }

    /// The one place that differs: after the type has read what it wants, nothing may be left.
    fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<V::Value, A::Error> {
        let mut seq = Counted {
            inner: seq,
            read: 0,
        };
        let value = self.0.visit_seq(&mut seq)?;
        let mut left = 0;
        while seq.inner.next_element::<IgnoredAny>()?.is_some() {
            left += 1;
        }
        if left > 0 {
            return Err(A::Error::invalid_length(
                seq.read + left,
                &"fewer elements in array",
            ));
        }
        Ok(value)
    }

    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<V::Value, A::Error> {
        self.0.visit_map(WholeArrays(map))
    }

    fn visit_enum<A: EnumAccess<'de>>(self, data: A) -> Result<V::Value, A::Error> {
        self.0.visit_enum(WholeArrays(data))
    }
}

/// A sequence whose elements are read through [`WholeArrays`], counted.
struct Counted<A> {
    inner: A,
    read: usize,
}

impl<'de, A: SeqAccess<'de>> SeqAccess<'de> for Counted<A> {
    type Error = A::Error;

    fn next_element_seed<T: DeserializeSeed<'de>>(
        &mut self,
        seed: T,
    ) -> Result<Option<T::Value>, A::Error> {
        let next = self.inner.next_element_seed(WholeArrays(seed))?;
        self.read += usize::from(next.is_some());
        Ok(next)
    }

    fn size_hint(&self) -> Option<usize> {
        self.inner.size_hint()
    }
}

impl<'de, T: DeserializeSeed<'de>> DeserializeSeed<'de> for WholeArrays<T> {
    type Value = T::Value;

    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<T::Value, D::Error> {
        self.0.deserialize(WholeArrays(d))
    }
}

impl<'de, A: MapAccess<'de>> MapAccess<'de> for WholeArrays<A> {
    type Error = A::Error;

    fn next_key_seed<K: DeserializeSeed<'de>>(
        &mut self,
        seed: K,
    ) -> Result<Option<K::Value>, A::Error> {
        self.0.next_key_seed(seed)
    }

    fn next_value_seed<S: DeserializeSeed<'de>>(&mut self, seed: S) -> Result<S::Value, A::Error> {
        self.0.next_value_seed(WholeArrays(seed))
    }

    fn size_hint(&self) -> Option<usize> {
        self.0.size_hint()
    }
}

impl<'de, A: EnumAccess<'de>> EnumAccess<'de> for WholeArrays<A> {
    type Error = A::Error;
    type Variant = WholeArrays<A::Variant>;

    fn variant_seed<S: DeserializeSeed<'de>>(
        self,
        seed: S,
    ) -> Result<(S::Value, Self::Variant), A::Error> {
        let (value, variant) = self.0.variant_seed(seed)?;
        Ok((value, WholeArrays(variant)))
    }
}

impl<'de, A: VariantAccess<'de>> VariantAccess<'de> for WholeArrays<A> {
    type Error = A::Error;

    fn unit_variant(self) -> Result<(), A::Error> {
        self.0.unit_variant()
    }

    fn newtype_variant_seed<S: DeserializeSeed<'de>>(self, seed: S) -> Result<S::Value, A::Error> {
        self.0.newtype_variant_seed(WholeArrays(seed))
    }

    fn tuple_variant<V: Visitor<'de>>(self, len: usize, visitor: V) -> Result<V::Value, A::Error> {
        self.0.tuple_variant(len, WholeArrays(visitor))
    }

    fn struct_variant<V: Visitor<'de>>(
        self,
        fields: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, A::Error> {
        self.0.struct_variant(fields, WholeArrays(visitor))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde::Deserialize;

    #[derive(Debug, Deserialize, PartialEq)]
    struct Axes {
        dph: [f64; 3],
        all: Vec<f64>,
    }

    fn read(text: &str) -> Result<Axes, String> {
        let doc = toml::de::DeTable::parse(text).unwrap();
        Axes::deserialize(WholeArrays(toml::de::Deserializer::from(doc))).map_err(|mut e| {
            e.set_input(Some(text));
            e.to_string()
        })
    }

    #[test]
    fn a_fixed_array_must_be_read_whole() {
        let ok = read("dph = [1.0, 2.0, 3.0]\nall = [1.0, 2.0, 3.0, 4.0]\n").unwrap();
        assert_eq!(ok.dph, [1.0, 2.0, 3.0]);
        assert_eq!(ok.all.len(), 4);
        let e = read("dph = [1.0, 2.0, 3.0, 4.0]\nall = []\n").unwrap_err();
        assert!(
            e.contains("line 1, column 7")
                && e.contains("invalid length 4, expected fewer elements in array"),
            "{e}"
        );
        let e = read("dph = [1.0, 2.0]\nall = []\n").unwrap_err();
        assert!(
            e.contains("invalid length 2, expected an array of length 3"),
            "{e}"
        );
        // toml's own reader alone keeps the first three and drops the fourth.
        let doc = toml::de::DeTable::parse("dph = [1.0, 2.0, 3.0, 4.0]\nall = []\n").unwrap();
        let dropped = Axes::deserialize(toml::de::Deserializer::from(doc)).unwrap();
        assert_eq!(dropped.dph, [1.0, 2.0, 3.0]);
    }
}
