//! Parameters by name: the description of each parameter of a law or effect, and
//! the fixed-size access every law and effect struct gets from one macro.
//!
//! A controller, a scenario file and an identification loop all name parameters by
//! their field name (`stiffness`, `restitution`, …). The names, units and meanings
//! are written once, beside the struct, by `law_parameters!`; the typed access it
//! generates (`to_array`, `from_array`, `parameter`, `parameter_mut`, `map_named`)
//! replaces any serialisation round-trip, so reading or setting a parameter costs a
//! string comparison and a copy.

/// Most parameters one law or effect has (variable stiffness has five).
pub const MAX_PARAMETERS: usize = 5;

/// Every parameter value of one law or effect, in its `PARAMETERS` order; no
/// allocator needed.
pub type ParameterValues<T> = heapless::Vec<T, MAX_PARAMETERS>;

/// One parameter of a law or effect, as described to users.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ParameterInfo {
    /// Field name, as in scenario files, physics files and `--set`.
    pub name: &'static str,
    /// SI unit (`-` for dimensionless).
    pub unit: &'static str,
    /// Symbol and meaning, e.g. `"k, contact stiffness"`.
    pub meaning: &'static str,
}

/// Position of parameter `name` in `parameters`.
pub(crate) fn index_of(parameters: &[ParameterInfo], name: &str) -> Option<usize> {
    parameters.iter().position(|p| p.name == name)
}

/// Typed parameter access for a law or effect struct, with one line per field:
/// `field: "unit", "symbol, meaning";`.
///
/// Generates `map` (through [`map_fields!`](super::map_fields)), the `PARAMETERS`
/// list in field order, `to_array`/`from_array`, `parameter`/`parameter_mut` by name
/// and `map_named`. The array length is the number of fields, so a law with a field
/// added cannot silently keep an old length; a compile-time check keeps it within
/// [`MAX_PARAMETERS`].
macro_rules! law_parameters {
    ($law:ident { $($field:ident: $unit:literal, $meaning:literal;)* }) => {
        $crate::law::map_fields!($law { $($field),* });

        // A struct with more parameters than `ParameterValues` holds fails to build.
        const _: () = assert!([$(stringify!($field)),*].len() <= $crate::law::MAX_PARAMETERS);

        impl<T> $law<T> {
            /// The parameters in field order: name, unit and meaning.
            pub const PARAMETERS: &'static [$crate::law::ParameterInfo] = &[$(
                $crate::law::ParameterInfo {
                    name: stringify!($field),
                    unit: $unit,
                    meaning: $meaning,
                }
            ),*];
        }

        impl<T: Copy> $law<T> {
            /// Every parameter's value, in [`Self::PARAMETERS`] order.
            #[inline]
            pub fn to_array(&self) -> [T; [$(stringify!($field)),*].len()] {
                [$(self.$field),*]
            }

            /// The value built from its parameters in [`Self::PARAMETERS`] order.
            #[inline]
            pub fn from_array(values: [T; [$(stringify!($field)),*].len()]) -> Self {
                let [$($field),*] = values;
                $law { $($field),* }
            }

            /// The value of parameter `name`; `None` if there is none of that name.
            #[inline]
            pub fn parameter(&self, name: &str) -> Option<T> {
                match name {
                    $(stringify!($field) => Some(self.$field),)*
                    _ => None,
                }
            }

            /// Parameter `name` to write; `None` if there is none of that name.
            #[inline]
            pub fn parameter_mut(&mut self, name: &str) -> Option<&mut T> {
                match name {
                    $(stringify!($field) => Some(&mut self.$field),)*
                    _ => None,
                }
            }

            /// The same value with every parameter replaced by `f(name, value)`,
            /// called in [`Self::PARAMETERS`] order.
            #[inline]
            pub fn map_named(self, mut f: impl FnMut(&'static str, T) -> T) -> Self {
                $law { $($field: f(stringify!($field), self.$field)),* }
            }
        }
    };
}
pub(crate) use law_parameters;
