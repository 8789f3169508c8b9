//! Parsers of the flags' values: the edge's ([`ikarus_edge::options`]), and the names of the
//! library's choice enums as clap value parsers.

use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use ikarus::Named;
pub use ikarus_edge::options::*;

/// A value parser for the names of `T` ([`Named::ALL`]), each listed with its summary in
/// `--help`, so that the flags take their names from the library's one table.
pub fn named<T: Named + Send + Sync>() -> impl TypedValueParser<Value = T> {
    PossibleValuesParser::new(T::ALL.iter().map(|v| PossibleValue::new(v.name()).help(v.summary())))
        .map(|name| T::from_name(&name).expect("clap accepts only the possible values"))
}
