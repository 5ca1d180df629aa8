//! The `declare!` macro: one declaration of the scene's parameters and
//! choices, section by section, from which come both the table of
//! parameters ([`super::all`]) and the scene file's sections (the serde
//! structs `shadelab-io` reads a file into).
//!
//! Each field of a section is declared in one of four forms:
//!
//! - `key: param(Kind) "help." { default: …, label: …, … }` — a parameter
//!   the file may leave out: a table entry (key `section.key`, the kind, the
//!   help, then the body's fields of [`Param`](super::Param)) and a field
//!   `Option<T>` of the section, `T` the kind's type ([`value_type!`]);
//! - `key: required(Kind) "help." { … }` — the same, but a section that is
//!   given must hold it (`[camera]`'s `eye`): the field is `T`;
//! - `key: choice(Type)` — one of a [`Choice`](crate::choice::Choice)'s
//!   names, optional: the schema's list of choices, and a field `Option<Type>`;
//! - `key: required_choice(Type)` — the same, required (a light's `kind`).
//!
//! Colours and vectors are read as exactly three numbers ([`three`]).

use serde::de::{Deserialize, Deserializer, Error};

/// Arrays of exactly three values: serde's `[T; 3]` reads three elements and
/// lets a fourth pass unseen, so `position = [1, 2, 3, 4]` would lose its
/// last number in silence.
pub(crate) fn three<'de, D, T>(d: D) -> Result<[T; 3], D::Error>
where
    D: Deserializer<'de>,
    T: Deserialize<'de>,
{
    let values = Vec::<T>::deserialize(d)?;
    let found = values.len();
    values
        .try_into()
        .map_err(|_| D::Error::invalid_length(found, &"an array of exactly 3 numbers"))
}

/// [`three`] for an optional key.
pub(crate) fn three_or_none<'de, D, T>(d: D) -> Result<Option<[T; 3]>, D::Error>
where
    D: Deserializer<'de>,
    T: Deserialize<'de>,
{
    three(d).map(Some)
}

/// The type a scene file holds a value of a [`Kind`](super::Kind) in.
macro_rules! value_type {
    (Number) => {
        f32
    };
    (Integer) => {
        u32
    };
    (Rgb) => {
        [i64; 3]
    };
    (Vec3) => {
        [f32; 3]
    };
    (Bool) => {
        bool
    };
    (Text) => {
        String
    };
}
pub(crate) use value_type;

/// A section's struct, its fields taken one at a time (each form of field
/// has its own serde attributes) into the braces, then written out.
macro_rules! section_struct {
    ($(#[$attr:meta])* $name:ident { $($done:tt)* }) => {
        $(#[$attr])*
        #[derive(Debug, Clone, Default, PartialEq, serde::Deserialize, serde::Serialize)]
        #[serde(deny_unknown_fields)]
        pub struct $name { $($done)* }
    };
    ($(#[$attr:meta])* $name:ident { $($done:tt)* } $field:ident param (Rgb) $help:literal; $($rest:tt)*) => {
        $crate::params::declare::section_struct!($(#[$attr])* $name { $($done)*
            #[doc = $help]
            #[serde(default, deserialize_with = "crate::params::declare::three_or_none")]
            pub $field: Option<[i64; 3]>,
        } $($rest)*);
    };
    ($(#[$attr:meta])* $name:ident { $($done:tt)* } $field:ident param (Vec3) $help:literal; $($rest:tt)*) => {
        $crate::params::declare::section_struct!($(#[$attr])* $name { $($done)*
            #[doc = $help]
            #[serde(default, deserialize_with = "crate::params::declare::three_or_none")]
            pub $field: Option<[f32; 3]>,
        } $($rest)*);
    };
    ($(#[$attr:meta])* $name:ident { $($done:tt)* } $field:ident param ($kind:ident) $help:literal; $($rest:tt)*) => {
        $crate::params::declare::section_struct!($(#[$attr])* $name { $($done)*
            #[doc = $help]
            #[serde(default)]
            pub $field: Option<$crate::params::declare::value_type!($kind)>,
        } $($rest)*);
    };
    ($(#[$attr:meta])* $name:ident { $($done:tt)* } $field:ident required (Vec3) $help:literal; $($rest:tt)*) => {
        $crate::params::declare::section_struct!($(#[$attr])* $name { $($done)*
            #[doc = $help]
            #[serde(deserialize_with = "crate::params::declare::three")]
            pub $field: [f32; 3],
        } $($rest)*);
    };
    ($(#[$attr:meta])* $name:ident { $($done:tt)* } $field:ident required ($kind:ident) $help:literal; $($rest:tt)*) => {
        $crate::params::declare::section_struct!($(#[$attr])* $name { $($done)*
            #[doc = $help]
            pub $field: $crate::params::declare::value_type!($kind),
        } $($rest)*);
    };
    ($(#[$attr:meta])* $name:ident { $($done:tt)* } $field:ident choice ($ty:ident); $($rest:tt)*) => {
        $crate::params::declare::section_struct!($(#[$attr])* $name { $($done)*
            #[doc = concat!("One of [`", stringify!($ty), "`]'s names; absent: its default.")]
            #[serde(default)]
            pub $field: Option<$ty>,
        } $($rest)*);
    };
    ($(#[$attr:meta])* $name:ident { $($done:tt)* } $field:ident required_choice ($ty:ident); $($rest:tt)*) => {
        $crate::params::declare::section_struct!($(#[$attr])* $name { $($done)*
            #[doc = concat!("One of [`", stringify!($ty), "`]'s names.")]
            pub $field: $ty,
        } $($rest)*);
    };
}
pub(crate) use section_struct;

/// A field's entry in the table of parameters (none for a choice).
macro_rules! param_entry {
    ($table:ident, $section:ident, $field:ident, choice, $ty:ident) => {};
    ($table:ident, $section:ident, $field:ident, required_choice, $ty:ident) => {};
    ($table:ident, $section:ident, $field:ident, $how:ident, $kind:ident, $help:literal, { $($body:tt)* }) => {
        $table.push($crate::params::Param {
            key: concat!(stringify!($section), ".", stringify!($field)),
            kind: $crate::params::Kind::$kind,
            help: $help,
            $($body)*
            ..$crate::params::Param::BLANK
        });
    };
}
pub(crate) use param_entry;

/// A field's list in the schema's choices (none for a parameter).
macro_rules! choice_entry {
    ($lists:ident, $section:ident, $field:ident, choice, $ty:ident) => {
        $lists.push($crate::params::choice_list::<$ty>(concat!(
            stringify!($section),
            ".",
            stringify!($field)
        )));
    };
    ($lists:ident, $section:ident, $field:ident, required_choice, $ty:ident) => {
        $crate::params::declare::choice_entry!($lists, $section, $field, choice, $ty);
    };
    ($lists:ident, $section:ident, $field:ident, $how:ident, $kind:ident) => {};
}
pub(crate) use choice_entry;

/// The declaration: each section's struct, [`table`](super::table) of its
/// parameters and `choice_lists` of its choices, in the order declared.
macro_rules! declare {
    ($(
        $(#[$attr:meta])*
        [$section:ident] $name:ident {
            $( $field:ident : $how:ident ($what:ident) $($help:literal { $($body:tt)* })? ),* $(,)?
        }
    )*) => {
        $(
            $crate::params::declare::section_struct!(
                $(#[$attr])* $name {} $( $field $how ($what) $($help)?; )*
            );
        )*

        /// Every parameter, in the order declared.
        #[allow(clippy::vec_init_then_push)] // pushed field by field: a choice adds none
        pub(super) fn table() -> Vec<$crate::params::Param> {
            let mut table = Vec::new();
            $($(
                $crate::params::declare::param_entry!(
                    table, $section, $field, $how, $what $(, $help, { $($body)* })?
                );
            )*)*
            table
        }

        /// Every choice's list for the schema, in the order declared.
        #[allow(clippy::vec_init_then_push)] // pushed field by field: a parameter adds none
        pub(super) fn choice_lists() -> Vec<serde_json::Value> {
            let mut lists = Vec::new();
            $($(
                $crate::params::declare::choice_entry!(lists, $section, $field, $how, $what);
            )*)*
            lists
        }
    };
}
pub(crate) use declare;
