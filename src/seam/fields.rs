//! Scene fields, declared once beside their spec.
//!
//! Each spec struct of a scene (`SolverSpec`, `SkiddingSpec`, `WearSpec`, the traction law,
//! the bearing, ...) carries `FIELDS`, a const table of [`FieldDecl`]: name, kind, unit,
//! bounds, what the bounds do not say, and meaning; specs with a `Default` declare each
//! field's default in the same row ([`declare_fields!`](crate::declare_fields)). From these
//! rows alone come
//! - the range checks of `Scene::validate` (in the component) and of the specs'
//!   `params()`: one generic checker, [`check`], reads the spec's serde serialisation and
//!   refuses a value outside its row naming the field, the value and the allowed range
//!   (only rules across several fields stay written by hand);
//! - the schema (`component::schema`): it mounts each spec's rows under the spec's prefix
//!   (the traction law's rows once, mounted under both `model.skidding.traction` and
//!   `model.full.traction`), which `raceway scene --explain`, `--check` and the scene
//!   documentation read;
//! - the FMI parameter ranges that are scene ranges ([`find`] is `const`, so
//!   `component::variables::RANGES` reads `solver.rtol`'s bounds from its row).
//!
//! A new scene option is one struct field and one row beside it, in one file.

use crate::error::{Error, Result};
use serde::ser::{self, Impossible, Serialize};

/// Named sets of allowed strings that come from the library's own lists.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Names {
    /// Bearing presets ([`crate::geometry::presets::presets`]).
    BearingPreset,
    /// Material presets ([`crate::geometry::Material::presets`]).
    Material,
    /// Lubricant presets.
    Lubricant,
}

impl Names {
    /// The allowed names.
    pub fn list(self) -> Vec<String> {
        use crate::geometry::{presets, Material};
        match self {
            Names::BearingPreset => presets::presets().into_iter().map(|p| p.name).collect(),
            Names::Material => Material::presets().into_iter().map(|m| m.name).collect(),
            Names::Lubricant => crate::lubrication::LUBRICANT_PRESETS
                .iter()
                .map(|s| s.to_string())
                .collect(),
        }
    }

    /// Is `name` allowed (bearing presets and materials ignore case, as the library does)?
    pub fn contains(self, name: &str) -> bool {
        use crate::geometry::{presets, Material};
        match self {
            Names::BearingPreset => {
                presets::preset(name).is_ok()
                    || crate::geometry::roller_catalogue::lookup(name).is_some()
            }
            Names::Material => Material::by_name(name).is_ok(),
            _ => self.list().iter().any(|n| n == name),
        }
    }
}

/// The type of a field.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Kind {
    /// A number (integers are accepted).
    Float,
    /// A non-negative integer.
    Int,
    /// Free text.
    Text,
    /// One of fixed spellings (a serde enum).
    Enum(&'static [&'static str]),
    /// One of the integers listed.
    IntChoice(&'static [i64]),
    /// A name from a library list.
    Name(Names),
    /// A name from a library list, or a table of fields (the paths below this one).
    NameOrTable(Names),
    /// `true` or `false`.
    Bool,
    /// A table of its own spec's fields, mounted by the schema under its own prefix (no
    /// row of its own).
    Table,
}

impl Kind {
    /// Short type name for the documentation.
    pub fn type_name(&self) -> &'static str {
        match self {
            Kind::Float => "number",
            Kind::Int | Kind::IntChoice(_) => "integer",
            Kind::Text | Kind::Enum(_) | Kind::Name(_) => "string",
            Kind::NameOrTable(_) => "string or table",
            Kind::Bool => "boolean",
            Kind::Table => "table",
        }
    }
}

/// Allowed interval of a number: `(value, inclusive)` at each end, `None` unbounded.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bounds {
    /// Lower end.
    pub lo: Option<(f64, bool)>,
    /// Upper end.
    pub hi: Option<(f64, bool)>,
}

/// Any finite number.
pub const ANY: Bounds = Bounds { lo: None, hi: None };
/// `> x`.
pub const fn gt(x: f64) -> Bounds {
    Bounds {
        lo: Some((x, false)),
        hi: None,
    }
}
/// `>= x`.
pub const fn ge(x: f64) -> Bounds {
    Bounds {
        lo: Some((x, true)),
        hi: None,
    }
}
/// An interval, each end open or closed.
pub const fn between(lo: f64, lo_in: bool, hi: f64, hi_in: bool) -> Bounds {
    Bounds {
        lo: Some((lo, lo_in)),
        hi: Some((hi, hi_in)),
    }
}
/// `[lo, hi]`.
pub const fn closed(lo: f64, hi: f64) -> Bounds {
    between(lo, true, hi, true)
}

impl Bounds {
    /// Does `v` lie inside (and is it finite)?
    pub fn contains(&self, v: f64) -> bool {
        v.is_finite()
            && self
                .lo
                .is_none_or(|(lo, inc)| if inc { v >= lo } else { v > lo })
            && self
                .hi
                .is_none_or(|(hi, inc)| if inc { v <= hi } else { v < hi })
    }

    /// `[0, 1]`, `(0, 1e4]`, `> 0`, `>= 1`, `any finite number`.
    pub fn text(&self) -> String {
        match (self.lo, self.hi) {
            (None, None) => "any finite number".into(),
            (Some((lo, inc)), None) => format!("{} {}", if inc { ">=" } else { ">" }, num(lo)),
            (None, Some((hi, inc))) => format!("{} {}", if inc { "<=" } else { "<" }, num(hi)),
            (Some((lo, li)), Some((hi, hi_in))) => format!(
                "{}{}, {}{}",
                if li { "[" } else { "(" },
                num(lo),
                num(hi),
                if hi_in { "]" } else { ")" }
            ),
        }
    }

    /// The lower end, `-inf` when open-ended (for `const` tables such as the FMI ranges).
    pub const fn min(&self) -> f64 {
        match self.lo {
            Some((x, _)) => x,
            None => f64::NEG_INFINITY,
        }
    }

    /// The upper end, `inf` when open-ended.
    pub const fn max(&self) -> f64 {
        match self.hi {
            Some((x, _)) => x,
            None => f64::INFINITY,
        }
    }
}

/// A bound as the documentation writes it.
pub fn num(x: f64) -> String {
    let a = x.abs();
    if a != 0.0 && !(1e-3..1e5).contains(&a) && !(x.fract() == 0.0 && a < 1e10) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

/// One field of a spec, declared once: its default is the spec's `Default` (declared in the
/// same row by [`declare_fields!`](crate::declare_fields)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FieldDecl {
    /// Key in the spec's table.
    pub name: &'static str,
    /// Type.
    pub kind: Kind,
    /// Unit (`-`: none).
    pub unit: &'static str,
    /// Numeric range (numbers only).
    pub bounds: Bounds,
    /// What the range does not say (bounds that depend on other fields, what absent means).
    pub note: &'static str,
    /// Why the range is what it is, added to a refusal (empty: nothing to add).
    pub why: &'static str,
    /// Meaning.
    pub description: &'static str,
}

const fn decl(
    kind: Kind,
    unit: &'static str,
    bounds: Bounds,
    description: &'static str,
) -> FieldDecl {
    FieldDecl {
        name: "",
        kind,
        unit,
        bounds,
        note: "",
        why: "",
        description,
    }
}

/// A number in `unit` within `bounds`.
pub const fn number(unit: &'static str, bounds: Bounds, description: &'static str) -> FieldDecl {
    decl(Kind::Float, unit, bounds, description)
}
/// A non-negative integer within `bounds`.
pub const fn integer(bounds: Bounds, description: &'static str) -> FieldDecl {
    decl(Kind::Int, "-", bounds, description)
}
/// One of the integers `choices`.
pub const fn int_choice(choices: &'static [i64], description: &'static str) -> FieldDecl {
    decl(Kind::IntChoice(choices), "-", ANY, description)
}
/// One of the `spellings` of a serde enum.
pub const fn choice(spellings: &'static [&'static str], description: &'static str) -> FieldDecl {
    decl(Kind::Enum(spellings), "-", ANY, description)
}
/// A name from a library list.
pub const fn name(names: Names, description: &'static str) -> FieldDecl {
    decl(Kind::Name(names), "-", ANY, description)
}
/// A name from a library list, or a table of fields.
pub const fn name_or_table(names: Names, description: &'static str) -> FieldDecl {
    decl(Kind::NameOrTable(names), "-", ANY, description)
}
/// Free text.
pub const fn text(description: &'static str) -> FieldDecl {
    decl(Kind::Text, "-", ANY, description)
}
/// `true` or `false`.
pub const fn flag(description: &'static str) -> FieldDecl {
    decl(Kind::Bool, "-", ANY, description)
}
/// A sub-table: another spec, mounted by the schema under its own prefix.
pub const fn table() -> FieldDecl {
    decl(Kind::Table, "-", ANY, "")
}

impl FieldDecl {
    /// The row with its key.
    pub const fn named(self, name: &'static str) -> FieldDecl {
        FieldDecl { name, ..self }
    }
    /// The row with what its range does not say.
    pub const fn note(self, note: &'static str) -> FieldDecl {
        FieldDecl { note, ..self }
    }
    /// The row with the reason of its range, added to a refusal.
    pub const fn why(self, why: &'static str) -> FieldDecl {
        FieldDecl { why, ..self }
    }

    /// What a refusal says is allowed: `a finite number in [0, 2]`, `an integer >= 1`,
    /// `one of 2, 5`, with the unit and the reason when the row has them.
    pub fn allowed(&self) -> String {
        let range = match (self.bounds.lo, self.bounds.hi) {
            (None, None) => String::new(),
            (Some(_), Some(_)) => format!(" in {}", self.bounds.text()),
            _ => format!(" {}", self.bounds.text()),
        };
        let unit = match self.unit {
            "-" | "" => String::new(),
            u if range.is_empty() => format!(" ({u})"),
            u => format!(" {u}"),
        };
        let why = if self.why.is_empty() {
            String::new()
        } else {
            format!(" ({})", self.why)
        };
        match self.kind {
            Kind::Int => format!("an integer{range}{why}"),
            Kind::IntChoice(v) => format!(
                "one of {}{why}",
                v.iter().map(i64::to_string).collect::<Vec<_>>().join(", ")
            ),
            _ => format!("a finite number{range}{unit}{why}"),
        }
    }
}

/// The row named `name` of `decls` (usable in `const` items; a missing row fails the build).
pub const fn find(decls: &'static [FieldDecl], name: &str) -> &'static FieldDecl {
    let mut i = 0;
    while i < decls.len() {
        let a = decls[i].name.as_bytes();
        let b = name.as_bytes();
        if a.len() == b.len() {
            let mut j = 0;
            while j < a.len() && a[j] == b[j] {
                j += 1;
            }
            if j == a.len() {
                return &decls[i];
            }
        }
        i += 1;
    }
    panic!("no such field declared")
}

/// Check every number of `spec` against its row of `decls`; the error names
/// `prefix.<field>`, the value and the allowed range. Absent optional fields, and fields of
/// other kinds (sub-tables, spellings, text: serde has checked those), are skipped.
pub fn check<T: Serialize + ?Sized>(prefix: &str, decls: &[FieldDecl], spec: &T) -> Result<()> {
    let fields = match spec.serialize(Flat) {
        Ok(Out::Fields(f)) => f,
        _ => Vec::new(),
    };
    for d in decls {
        let Some((_, leaf)) = fields.iter().find(|(k, _)| *k == d.name) else {
            continue;
        };
        let path = || {
            if prefix.is_empty() {
                d.name.to_string()
            } else {
                format!("{prefix}.{}", d.name)
            }
        };
        let ok = match (d.kind, leaf) {
            (Kind::Float, Leaf::F(v)) => d.bounds.contains(*v),
            (Kind::Float | Kind::Int, Leaf::I(i)) => d.bounds.contains(*i as f64),
            (Kind::IntChoice(v), Leaf::I(i)) => v.iter().any(|x| *x as i128 == *i),
            _ => true,
        };
        if !ok {
            let value = match leaf {
                Leaf::F(v) => v.to_string(),
                Leaf::I(i) => i.to_string(),
                _ => String::new(),
            };
            return Err(Error::invalid(path(), value, d.allowed()));
        }
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------
// The serialisation the checker reads: a struct's fields as numbers (or not numbers).

/// One field's value as the checker sees it.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Leaf {
    F(f64),
    I(i128),
    /// Absent (`None`).
    Absent,
    /// Text, a boolean, a spelling, a table or a list.
    Other,
}

enum Out {
    Leaf(Leaf),
    Fields(Vec<(&'static str, Leaf)>),
}

#[derive(Debug)]
struct NotFlat;

impl std::fmt::Display for NotFlat {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("not a flat value")
    }
}
impl std::error::Error for NotFlat {}
impl ser::Error for NotFlat {
    fn custom<M: std::fmt::Display>(_: M) -> Self {
        NotFlat
    }
}

/// A serializer that keeps a struct's top-level fields as [`Leaf`]s (NaN stays NaN, a
/// `u64` stays exact).
struct Flat;

struct Collect(Vec<(&'static str, Leaf)>);

impl ser::SerializeStruct for Collect {
    type Ok = Out;
    type Error = NotFlat;
    fn serialize_field<V: Serialize + ?Sized>(
        &mut self,
        key: &'static str,
        v: &V,
    ) -> std::result::Result<(), NotFlat> {
        let leaf = match v.serialize(Flat) {
            Ok(Out::Leaf(l)) => l,
            _ => Leaf::Other,
        };
        self.0.push((key, leaf));
        Ok(())
    }
    fn end(self) -> std::result::Result<Out, NotFlat> {
        Ok(Out::Fields(self.0))
    }
}

macro_rules! leaf {
    ($($f:ident: $t:ty => $e:expr;)*) => {
        $(fn $f(self, v: $t) -> std::result::Result<Out, NotFlat> {
            #[allow(clippy::redundant_closure_call)]
            Ok(Out::Leaf(($e)(v)))
        })*
    };
}

impl ser::Serializer for Flat {
    type Ok = Out;
    type Error = NotFlat;
    type SerializeSeq = Impossible<Out, NotFlat>;
    type SerializeTuple = Impossible<Out, NotFlat>;
    type SerializeTupleStruct = Impossible<Out, NotFlat>;
    type SerializeTupleVariant = Impossible<Out, NotFlat>;
    type SerializeMap = Impossible<Out, NotFlat>;
    type SerializeStruct = Collect;
    type SerializeStructVariant = Impossible<Out, NotFlat>;

    leaf! {
        serialize_bool: bool => |_| Leaf::Other;
        serialize_i8: i8 => |v| Leaf::I(v as i128);
        serialize_i16: i16 => |v| Leaf::I(v as i128);
        serialize_i32: i32 => |v| Leaf::I(v as i128);
        serialize_i64: i64 => |v| Leaf::I(v as i128);
        serialize_i128: i128 => Leaf::I;
        serialize_u8: u8 => |v| Leaf::I(v as i128);
        serialize_u16: u16 => |v| Leaf::I(v as i128);
        serialize_u32: u32 => |v| Leaf::I(v as i128);
        serialize_u64: u64 => |v| Leaf::I(v as i128);
        serialize_f32: f32 => |v| Leaf::F(v as f64);
        serialize_f64: f64 => Leaf::F;
        serialize_char: char => |_| Leaf::Other;
        serialize_str: &str => |_| Leaf::Other;
        serialize_bytes: &[u8] => |_| Leaf::Other;
    }
    fn serialize_none(self) -> std::result::Result<Out, NotFlat> {
        Ok(Out::Leaf(Leaf::Absent))
    }
    fn serialize_some<V: Serialize + ?Sized>(self, v: &V) -> std::result::Result<Out, NotFlat> {
        v.serialize(Flat)
    }
    fn serialize_unit(self) -> std::result::Result<Out, NotFlat> {
        Ok(Out::Leaf(Leaf::Other))
    }
    fn serialize_unit_struct(self, _: &'static str) -> std::result::Result<Out, NotFlat> {
        Ok(Out::Leaf(Leaf::Other))
    }
    fn serialize_unit_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
    ) -> std::result::Result<Out, NotFlat> {
        Ok(Out::Leaf(Leaf::Other))
    }
    fn serialize_newtype_struct<V: Serialize + ?Sized>(
        self,
        _: &'static str,
        v: &V,
    ) -> std::result::Result<Out, NotFlat> {
        v.serialize(Flat)
    }
    fn serialize_newtype_variant<V: Serialize + ?Sized>(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: &V,
    ) -> std::result::Result<Out, NotFlat> {
        Ok(Out::Leaf(Leaf::Other))
    }
    fn serialize_seq(self, _: Option<usize>) -> std::result::Result<Self::SerializeSeq, NotFlat> {
        Err(NotFlat)
    }
    fn serialize_tuple(self, _: usize) -> std::result::Result<Self::SerializeTuple, NotFlat> {
        Err(NotFlat)
    }
    fn serialize_tuple_struct(
        self,
        _: &'static str,
        _: usize,
    ) -> std::result::Result<Self::SerializeTupleStruct, NotFlat> {
        Err(NotFlat)
    }
    fn serialize_tuple_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> std::result::Result<Self::SerializeTupleVariant, NotFlat> {
        Err(NotFlat)
    }
    fn serialize_map(self, _: Option<usize>) -> std::result::Result<Self::SerializeMap, NotFlat> {
        Err(NotFlat)
    }
    fn serialize_struct(
        self,
        _: &'static str,
        len: usize,
    ) -> std::result::Result<Collect, NotFlat> {
        Ok(Collect(Vec::with_capacity(len)))
    }
    fn serialize_struct_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> std::result::Result<Self::SerializeStructVariant, NotFlat> {
        Err(NotFlat)
    }
}

/// Declare a spec's fields once: one row per struct field, `field: default => declaration`,
/// giving the spec its `FIELDS` table and its `Default` (the defaults of the rows). Specs
/// without a `Default` (required fields) write `field => declaration`.
///
/// ```
/// use raceway::component::fields::{check, gt, number};
///
/// #[derive(serde::Serialize)]
/// struct Demo {
///     gain: f64,
/// }
/// raceway::declare_fields!(Demo {
///     gain: 2.0 => number("-", gt(0.0), "a gain"),
/// });
/// assert_eq!(Demo::default().gain, 2.0);
/// assert_eq!((Demo::FIELDS[0].name, Demo::FIELDS[0].description), ("gain", "a gain"));
/// let e = check("demo", Demo::FIELDS, &Demo { gain: 0.0 }).unwrap_err();
/// assert_eq!(e.to_string(), "invalid `demo.gain` = 0: allowed a finite number > 0");
/// ```
#[macro_export]
macro_rules! declare_fields {
    ($ty:ident { $($field:ident : $default:expr => $decl:expr),* $(,)? }) => {
        impl $ty {
            /// The fields of this spec, declared once (their defaults are [`Default`]'s).
            pub const FIELDS: &'static [$crate::seam::fields::FieldDecl] =
                &[$($decl.named(stringify!($field))),*];
        }
        impl Default for $ty {
            fn default() -> Self {
                $ty { $($field: $default),* }
            }
        }
    };
    ($ty:ident { $($field:ident => $decl:expr),* $(,)? }) => {
        impl $ty {
            /// The fields of this spec, declared once.
            pub const FIELDS: &'static [$crate::seam::fields::FieldDecl] =
                &[$($decl.named(stringify!($field))),*];
        }
    };
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(serde::Serialize)]
    struct S {
        a: f64,
        b: Option<f64>,
        n: u64,
        k: u32,
        s: String,
    }

    const DECLS: &[FieldDecl] = &[
        number("m", closed(0.0, 1.0), "a").named("a"),
        number("-", gt(0.0), "b").named("b"),
        integer(ge(0.0), "n").named("n"),
        int_choice(&[2, 5], "k").named("k"),
        text("s").named("s"),
    ];

    fn s() -> S {
        S {
            a: 0.5,
            b: None,
            n: u64::MAX,
            k: 2,
            s: "x".into(),
        }
    }

    #[test]
    fn the_checker_refuses_what_the_rows_refuse_and_names_the_field() {
        assert!(
            check("p", DECLS, &s()).is_ok(),
            "absent optional, u64::MAX exact"
        );
        let e = check("p", DECLS, &S { a: f64::NAN, ..s() })
            .unwrap_err()
            .to_string();
        assert_eq!(
            e,
            "invalid `p.a` = NaN: allowed a finite number in [0, 1] m"
        );
        let e = check(
            "p",
            DECLS,
            &S {
                b: Some(0.0),
                ..s()
            },
        )
        .unwrap_err()
        .to_string();
        assert_eq!(e, "invalid `p.b` = 0: allowed a finite number > 0");
        let e = check("p", DECLS, &S { k: 3, ..s() })
            .unwrap_err()
            .to_string();
        assert_eq!(e, "invalid `p.k` = 3: allowed one of 2, 5");
        assert!(check(
            "p",
            DECLS,
            &S {
                b: Some(f64::INFINITY),
                ..s()
            }
        )
        .is_err());
    }

    #[test]
    fn find_reads_a_row_in_const_context() {
        const B: Bounds = find(DECLS, "a").bounds;
        assert_eq!((B.min(), B.max()), (0.0, 1.0));
    }
}
