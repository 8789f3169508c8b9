//! Names at the edges: the one table of short names, labels and summaries of the library's
//! choice enums ([`Method`](crate::Method), [`LimitMode`](crate::LimitMode),
//! [`EaseKind`](crate::EaseKind),
//! [`Interpolation`](crate::motion::Interpolation)).
//!
//! The command line's value parsers, the arm files, the HTTP API and the playground's select
//! lists all read these tables, so a new variant is named in exactly one place: its `match` arm
//! in the enum's [`Named::name`], which fails to compile until it is written.

use thiserror::Error;

/// Declares a fieldless enum and its `ALL` list from one list of variants, so that no variant
/// can be left out of `ALL` (and so out of the edges' parsing, the tests' loops and
/// `/api/meta`): a derived list, without a dependency (`strum`'s `VariantArray` would do the
/// same with two crates more in every build of every edge).
///
/// Write the enum as usual inside the macro, its attributes (derives, docs, `#[default]`,
/// `#[serde(…)]`, `#[value(…)]`) and its variants' attributes included; variants take neither
/// fields nor explicit discriminants. The enum gets an inherent
/// `pub const ALL: [Self; N]`, every variant once in the order declared. Adding a variant then
/// needs no second edit; matching on the enum without a catch-all arm makes the compiler name
/// every `match` the new variant must join.
///
/// ```
/// ikarus::listed_enum! {
///     /// A traffic light's colours.
///     #[derive(Debug, Clone, Copy, PartialEq, Eq)]
///     pub enum Light {
///         /// Go.
///         Green,
///         Amber,
///         Red,
///     }
/// }
///
/// assert_eq!(Light::ALL, [Light::Green, Light::Amber, Light::Red]);
/// ```
#[macro_export]
macro_rules! listed_enum {
    (
        $(#[$meta:meta])*
        $vis:vis enum $name:ident {
            $( $(#[$vmeta:meta])* $variant:ident ),+ $(,)?
        }
    ) => {
        $(#[$meta])*
        $vis enum $name {
            $( $(#[$vmeta])* $variant ),+
        }

        impl $name {
            /// Every variant, in the order declared (generated with the enum: none is left out).
            pub const ALL: [$name; [$(stringify!($variant)),+].len()] = [$($name::$variant),+];
        }
    };
}

/// An enum whose variants are chosen by name at the edges (flags, files, requests).
pub trait Named: Copy + Sized + 'static {
    /// What the edges call this kind of choice (`"method"`, `"limit mode"`, `"ease"`).
    const KIND: &'static str;

    /// Every variant, in a stable order (the order of help texts and select lists).
    const ALL: &'static [Self];

    /// The short name used at the edges, lowercase ASCII.
    fn name(self) -> &'static str;

    /// A label for people (a select list's text).
    fn label(self) -> &'static str;

    /// One line saying what the variant does (a flag's help text).
    fn summary(self) -> &'static str;

    /// The variant called `name`.
    #[must_use]
    fn from_name(name: &str) -> Option<Self> {
        Self::ALL.iter().copied().find(|v| v.name() == name)
    }

    /// The short names of [`Named::ALL`], in order.
    #[must_use]
    fn names() -> Vec<&'static str> {
        Self::ALL.iter().map(|v| v.name()).collect()
    }

    /// Like [`Named::from_name`], with an error that lists the valid names.
    fn parse_name(name: &str) -> Result<Self, UnknownName> {
        Self::from_name(name).ok_or_else(|| UnknownName {
            kind: Self::KIND,
            got: name.to_owned(),
            expected: Self::names().join(", "),
        })
    }
}

/// A name that no variant has.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[error("unknown {kind} '{got}' (expected one of: {expected})")]
pub struct UnknownName {
    /// What kind of choice was named (`"method"`, …).
    pub kind: &'static str,
    /// The name given.
    pub got: String,
    /// The valid names, comma-separated.
    pub expected: String,
}

/// [`Named`] for an enum with inherent `ALL`, `name`, `label` and `summary` (its one table),
/// and `Display`, `FromStr` and (with the `serde` feature) serde by [`Named::name`].
macro_rules! by_name {
    ($t:ty, $kind:literal) => {
        impl $crate::names::Named for $t {
            const KIND: &'static str = $kind;
            const ALL: &'static [Self] = &<$t>::ALL;
            fn name(self) -> &'static str {
                <$t>::name(self)
            }
            fn label(self) -> &'static str {
                <$t>::label(self)
            }
            fn summary(self) -> &'static str {
                <$t>::summary(self)
            }
        }

        impl std::fmt::Display for $t {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str($crate::names::Named::name(*self))
            }
        }

        impl std::str::FromStr for $t {
            type Err = $crate::names::UnknownName;
            fn from_str(s: &str) -> Result<Self, Self::Err> {
                <$t as $crate::names::Named>::parse_name(s)
            }
        }

        #[cfg(feature = "serde")]
        impl serde::Serialize for $t {
            fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                s.serialize_str($crate::names::Named::name(*self))
            }
        }

        #[cfg(feature = "serde")]
        impl<'de> serde::Deserialize<'de> for $t {
            fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
                struct Visitor;
                impl serde::de::Visitor<'_> for Visitor {
                    type Value = $t;
                    fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                        write!(f, "a {} name", <$t as $crate::names::Named>::KIND)
                    }
                    fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<$t, E> {
                        <$t as $crate::names::Named>::from_name(v).ok_or_else(|| {
                            // serde's own wording for an unknown variant.
                            let names: Vec<String> = <$t as $crate::names::Named>::ALL
                                .iter()
                                .map(|m| format!("`{}`", $crate::names::Named::name(*m)))
                                .collect();
                            E::custom(format_args!("unknown variant `{v}`, expected one of {}", names.join(", ")))
                        })
                    }
                }
                d.deserialize_str(Visitor)
            }
        }
    };
}

pub(crate) use by_name;

#[cfg(test)]
mod tests {
    crate::listed_enum! {
        /// Three variants, one with attributes of its own.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
        enum Three {
            /// The first.
            First,
            #[default]
            Second,
            Third,
        }
    }

    #[test]
    fn a_listed_enum_lists_every_variant_in_the_order_declared() {
        assert_eq!(Three::ALL, [Three::First, Three::Second, Three::Third]);
        assert_eq!(Three::default(), Three::Second);
        for (k, v) in Three::ALL.iter().enumerate() {
            assert_eq!(*v as usize, k);
        }
        // The library's choice enums: every variant once, in the order declared.
        for (k, v) in crate::Method::ALL.iter().enumerate() {
            assert_eq!(*v as usize, k);
        }
        for (k, v) in crate::LimitMode::ALL.iter().enumerate() {
            assert_eq!(*v as usize, k);
        }
    }
}
