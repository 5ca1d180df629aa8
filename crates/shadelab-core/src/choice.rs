//! A user-facing choice among named values — the shading method, the
//! specular term, the rasterizer, how polygons and attributes are
//! interpolated — declared once with the `choices!` macro of this module.
//!
//! The declaration gives each value its name (the one spelling used in scene
//! files, on the command line, by the Python package, the wasm ABI and the
//! page) and a line of help. From it come the inherent `ALL`, `name()` and
//! `help()`, [`Display`](std::fmt::Display), [`FromStr`](std::str::FromStr)
//! (ASCII case ignored), serde (exact names; an unknown one is refused with
//! the list of names) and the [`Choice`] trait, through which the command
//! line builds its parsers and help without a second list.

use crate::text::escape_token;

/// A value chosen by name among a fixed list.
pub trait Choice: Copy + PartialEq + Sized + 'static {
    /// What is chosen, for messages ("shading method").
    const WHAT: &'static str;
    /// Every value, in the order they are shown.
    const VALUES: &'static [Self];
    /// The value's name.
    fn name(self) -> &'static str;
    /// One line saying what the value means.
    fn help(self) -> &'static str;

    /// The value named `s` (ASCII case ignored).
    ///
    /// # Errors
    /// [`UnknownChoice`] naming what was given and what is allowed.
    fn from_name(s: &str) -> Result<Self, UnknownChoice> {
        Self::VALUES
            .iter()
            .copied()
            .find(|v| v.name().eq_ignore_ascii_case(s))
            .ok_or_else(|| UnknownChoice {
                what: Self::WHAT,
                given: s.to_owned(),
                expected: Self::VALUES
                    .iter()
                    .map(|v| v.name())
                    .collect::<Vec<_>>()
                    .join(", "),
            })
    }
}

/// A name that is none of a choice's values.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown {what} \"{}\": expected one of {expected}", escape_token(.given))]
pub struct UnknownChoice {
    /// What was being chosen.
    pub what: &'static str,
    /// The name given.
    pub given: String,
    /// The allowed names, comma-separated.
    pub expected: String,
}

/// Declares an existing enum a [`Choice`]: each variant with its name and
/// help, once.
///
/// For example `choices!(Shading, "shading method", { Flat => "flat": "one
/// lighting evaluation per polygon", ... })`.
macro_rules! choices {
    ($ty:ident, $what:literal, { $($variant:ident => $name:literal : $help:literal),+ $(,)? }) => {
        impl $ty {
            /// Every value, in the order they are shown.
            pub const ALL: [$ty; [$(stringify!($variant)),+].len()] = [$($ty::$variant),+];

            /// The name used in scene files, on the command line and by the page.
            pub fn name(self) -> &'static str {
                match self {
                    $($ty::$variant => $name,)+
                }
            }

            /// One line saying what the value means.
            pub fn help(self) -> &'static str {
                match self {
                    $($ty::$variant => $help,)+
                }
            }
        }

        impl crate::choice::Choice for $ty {
            const WHAT: &'static str = $what;
            const VALUES: &'static [$ty] = &$ty::ALL;
            fn name(self) -> &'static str {
                $ty::name(self)
            }
            fn help(self) -> &'static str {
                $ty::help(self)
            }
        }

        impl ::std::fmt::Display for $ty {
            fn fmt(&self, f: &mut ::std::fmt::Formatter<'_>) -> ::std::fmt::Result {
                f.write_str(self.name())
            }
        }

        impl ::std::str::FromStr for $ty {
            type Err = crate::choice::UnknownChoice;
            fn from_str(s: &str) -> Result<$ty, crate::choice::UnknownChoice> {
                <$ty as crate::choice::Choice>::from_name(s)
            }
        }

        impl ::serde::Serialize for $ty {
            fn serialize<S: ::serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                s.serialize_str(self.name())
            }
        }

        impl<'de> ::serde::Deserialize<'de> for $ty {
            fn deserialize<D: ::serde::Deserializer<'de>>(d: D) -> Result<$ty, D::Error> {
                const NAMES: &[&str] = &[$($name),+];
                let s = <::std::borrow::Cow<'de, str> as ::serde::Deserialize>::deserialize(d)?;
                $ty::ALL
                    .into_iter()
                    .find(|v| v.name() == s)
                    .ok_or_else(|| <D::Error as ::serde::de::Error>::unknown_variant(&s, NAMES))
            }
        }
    };
}

#[cfg(test)]
mod tests {
    use serde::de::value::{Error, StrDeserializer};
    use serde::Deserialize;

    use super::Choice;
    use crate::light::Specular;
    use crate::scene::{Interpolation, Polygons, Rasterizer, Shading};

    /// Every value's name reads back as that value, by `FromStr` (any ASCII
    /// case) and by serde (exactly), and `Display` writes the name.
    fn round_trips<T>()
    where
        T: Choice + std::fmt::Debug + std::fmt::Display + std::str::FromStr,
        T: for<'de> Deserialize<'de>,
        <T as std::str::FromStr>::Err: std::fmt::Debug,
    {
        let mut names: Vec<&str> = T::VALUES.iter().map(|v| v.name()).collect();
        for &v in T::VALUES {
            assert_eq!(v.to_string(), v.name());
            assert_eq!(v.name().parse::<T>().unwrap(), v);
            assert_eq!(v.name().to_ascii_uppercase().parse::<T>().unwrap(), v);
            let read = T::deserialize(StrDeserializer::<Error>::new(v.name())).unwrap();
            assert_eq!(read, v);
            assert!(!v.help().is_empty(), "{v:?} has no help");
        }
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), T::VALUES.len(), "{}: names repeat", T::WHAT);
    }

    #[test]
    fn every_choice_round_trips_through_its_names() {
        round_trips::<Shading>();
        round_trips::<Specular>();
        round_trips::<Rasterizer>();
        round_trips::<Polygons>();
        round_trips::<Interpolation>();
        assert_eq!(
            Shading::ALL,
            [Shading::Flat, Shading::Gouraud, Shading::Phong]
        );
        assert_eq!(Specular::BlinnPhong.name(), "blinn-phong");
    }

    #[test]
    fn an_unknown_name_is_refused_with_the_allowed_ones() {
        let e = "smooth".parse::<Shading>().unwrap_err();
        assert_eq!(
            e.to_string(),
            "unknown shading method \"smooth\": expected one of flat, gouraud, phong"
        );
        let e = "\u{1b}[31mred".parse::<Rasterizer>().unwrap_err();
        assert!(!e.to_string().contains('\u{1b}'), "{e}");
        // A scene file is exact: serde takes only the names as written.
        let e = Shading::deserialize(StrDeserializer::<Error>::new("Phong")).unwrap_err();
        assert_eq!(
            e.to_string(),
            "unknown variant `Phong`, expected one of `flat`, `gouraud`, `phong`"
        );
    }
}
