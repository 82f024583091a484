//! A reader of spanned TOML values: numbers, strings, vectors and tables
//! with the line of every key kept, unknown keys refused, and positions
//! moved into the scene's local frame. The schema ([`super::schema`]) says
//! which keys a scene has.

use super::document::SceneFileError;
use glam::DVec3;
use prismatic_core::Vec3;
use std::collections::HashMap;
use std::ops::Range;
use std::path::PathBuf;
use toml::Spanned;
use toml::de::{DeTable, DeValue};

/// Reads one scene file's values, keeping the line of every key.
pub struct Reader<'s> {
    /// The file's text.
    pub source: &'s str,
    /// Its name, for errors.
    pub file: &'s str,
    /// Where paths the file names are relative to.
    pub base: Option<PathBuf>,
    /// The line of every key read.
    pub lines: HashMap<String, usize>,
    /// Subtracted (in f64) from every position read.
    pub origin: DVec3,
    /// What was left out of placed glTF files.
    pub warnings: Vec<String>,
}

/// A scene whose camera lies farther than this from the world origin (in
/// any coordinate) is recentred on its camera: positions are read in f64
/// and stored in f32 relative to the camera, where f32 is precise. Closer
/// scenes keep world coordinates (f32 resolves 6e-5 at 1,024).
pub const LOCAL_FRAME_RADIUS: f64 = 1024.0;

/// A reader's result: a value or the file error.
pub type Result<T, E = SceneFileError> = std::result::Result<T, E>;

/// A table being read, with its key prefix.
pub struct Table<'a, 'i> {
    /// Its key (`object[2]`).
    pub key: String,
    /// Its source span.
    pub span: Range<usize>,
    /// Its entries.
    pub entries: &'a DeTable<'i>,
}

impl<'s> Reader<'s> {
    pub fn line_of(&self, offset: usize) -> usize {
        self.source[..offset.min(self.source.len())].matches('\n').count() + 1
    }

    pub fn err(&self, key: &str, span: &Range<usize>, reason: impl Into<String>) -> SceneFileError {
        SceneFileError {
            file: self.file.to_string(),
            line: Some(self.line_of(span.start)),
            key: key.to_string(),
            reason: reason.into(),
        }
    }

    pub fn table<'a, 'i>(&self, key: &str, v: &'a Spanned<DeValue<'i>>) -> Result<Table<'a, 'i>> {
        match v.get_ref() {
            DeValue::Table(t) => Ok(Table { key: key.to_string(), span: v.span(), entries: t }),
            other => Err(self.err(key, &v.span(), format!("must be a table, got {}", other.type_str()))),
        }
    }

    /// Rejects keys of `t` not in `allowed`, and records the lines of the others.
    pub fn check_keys(&mut self, t: &Table<'_, '_>, allowed: &[&str]) -> Result<()> {
        for (k, v) in t.entries.iter() {
            let name = k.get_ref().as_ref();
            let key = join(&t.key, name);
            if !allowed.contains(&name) {
                return Err(self.err(&key, &k.span(), format!("unknown key; expected one of: {}", allowed.join(", "))));
            }
            let line = self.line_of(v.span().start);
            self.lines.insert(key, line);
        }
        Ok(())
    }

    pub fn get<'a, 'i>(&self, t: &Table<'a, 'i>, field: &str) -> Option<&'a Spanned<DeValue<'i>>> {
        t.entries.iter().find(|(k, _)| k.get_ref().as_ref() == field).map(|(_, v)| v)
    }

    pub fn required<'a, 'i>(&self, t: &Table<'a, 'i>, field: &str) -> Result<&'a Spanned<DeValue<'i>>> {
        self.get(t, field).ok_or_else(|| self.err(&join(&t.key, field), &t.span, "is required but missing"))
    }

    pub fn number(&self, key: &str, v: &Spanned<DeValue<'_>>) -> Result<f64> {
        match v.get_ref() {
            DeValue::Float(f) => {
                f.as_str().parse::<f64>().map_err(|_| self.err(key, &v.span(), "is not a valid number"))
            }
            DeValue::Integer(i) => i64::from_str_radix(i.as_str(), i.radix())
                .map(|i| i as f64)
                .map_err(|_| self.err(key, &v.span(), "is not a valid number")),
            other => Err(self.err(key, &v.span(), format!("must be a number, got {}", other.type_str()))),
        }
    }

    pub fn float(&self, key: &str, v: &Spanned<DeValue<'_>>) -> Result<f32> {
        let x = self.number(key, v)?;
        if x.is_finite() && x.abs() > f64::from(f32::MAX) {
            return Err(self.err(key, &v.span(), format!("{x} is out of range")));
        }
        Ok(x as f32)
    }

    pub fn uint(&self, key: &str, v: &Spanned<DeValue<'_>>, max: u64) -> Result<u64> {
        match v.get_ref() {
            DeValue::Integer(i) => match i64::from_str_radix(i.as_str(), i.radix()) {
                Ok(n) if n >= 0 && n as u64 <= max => Ok(n as u64),
                Ok(n) => Err(self.err(key, &v.span(), format!("must be between 0 and {max}, got {n}"))),
                Err(_) => Err(self.err(key, &v.span(), "is not a valid integer")),
            },
            other => Err(self.err(key, &v.span(), format!("must be a whole number, got {}", other.type_str()))),
        }
    }

    pub fn boolean(&self, key: &str, v: &Spanned<DeValue<'_>>) -> Result<bool> {
        v.get_ref()
            .as_bool()
            .ok_or_else(|| self.err(key, &v.span(), format!("must be true or false, got {}", v.get_ref().type_str())))
    }

    pub fn string<'a>(&self, key: &str, v: &'a Spanned<DeValue<'_>>) -> Result<&'a str> {
        v.get_ref()
            .as_str()
            .ok_or_else(|| self.err(key, &v.span(), format!("must be a string, got {}", v.get_ref().type_str())))
    }

    pub fn array<'a, 'i>(&self, key: &str, v: &'a Spanned<DeValue<'i>>) -> Result<&'a [Spanned<DeValue<'i>>]> {
        match v.get_ref() {
            DeValue::Array(a) => Ok(a),
            other => Err(self.err(key, &v.span(), format!("must be an array, got {}", other.type_str()))),
        }
    }

    pub fn floats(&self, key: &str, v: &Spanned<DeValue<'_>>) -> Result<Vec<f64>> {
        self.array(key, v)?.iter().enumerate().map(|(i, x)| self.number(&format!("{key}[{i}]"), x)).collect()
    }

    /// A direction or a colour (not moved with the local frame).
    pub fn vec3(&self, key: &str, v: &Spanned<DeValue<'_>>) -> Result<Vec3> {
        let p = self.dvec3(key, v)?;
        match (0..3).find(|&i| p[i].is_finite() && p[i].abs() > f64::from(f32::MAX)) {
            Some(i) => Err(self.err(&format!("{key}[{i}]"), &v.span(), format!("{} is out of range", p[i]))),
            None => Ok(p.as_vec3()),
        }
    }

    pub fn dvec3(&self, key: &str, v: &Spanned<DeValue<'_>>) -> Result<DVec3> {
        let a = self.array(key, v)?;
        if a.len() != 3 {
            return Err(self.err(
                key,
                &v.span(),
                format!("must be an array of three numbers, got {} elements", a.len()),
            ));
        }
        let c: Vec<f64> =
            a.iter().enumerate().map(|(i, x)| self.number(&format!("{key}[{i}]"), x)).collect::<Result<_>>()?;
        Ok(DVec3::new(c[0], c[1], c[2]))
    }

    /// A position: read in f64, relative to the scene's local frame, then f32.
    pub fn point(&self, key: &str, v: &Spanned<DeValue<'_>>) -> Result<Vec3> {
        let p = self.dvec3(key, v)?;
        self.local(p).ok_or_else(|| self.err(key, &v.span(), format!("{p} is out of range")))
    }

    /// A file the scene names (mesh, index table, glTF), relative to the scene file.
    pub fn beside(&self, rel: &str) -> PathBuf {
        self.base.as_deref().map_or_else(|| PathBuf::from(rel), |b| b.join(rel))
    }

    /// World position `p` in the local frame (`None` beyond f32's range).
    pub fn local(&self, p: DVec3) -> Option<Vec3> {
        let local = p - self.origin;
        (!local.is_finite() || local.abs().max_element() <= f64::from(f32::MAX)).then(|| local.as_vec3())
    }

    pub fn opt<T>(
        &self,
        t: &Table<'_, '_>,
        field: &str,
        read: impl FnOnce(&Self, &str, &Spanned<DeValue<'_>>) -> Result<T>,
    ) -> Result<Option<T>> {
        self.get(t, field).map(|v| read(self, &join(&t.key, field), v)).transpose()
    }

    pub fn req<T>(
        &self,
        t: &Table<'_, '_>,
        field: &str,
        read: impl FnOnce(&Self, &str, &Spanned<DeValue<'_>>) -> Result<T>,
    ) -> Result<T> {
        let v = self.required(t, field)?;
        read(self, &join(&t.key, field), v)
    }
}

/// `prefix.field`, or `field` at the top.
pub fn join(prefix: &str, field: &str) -> String {
    if prefix.is_empty() { field.to_string() } else { format!("{prefix}.{field}") }
}
