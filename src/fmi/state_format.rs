//! The byte format of a saved FMU state (fmi2GetFMUstate, fmi2SerializeFMUstate): versioned, without
//! pointers, little-endian, closed by a checksum, so a state saved in one process restores in another.
//!
//! The saved-data envelope (`envelope`: magic `PFMUSTAT`, format version, length, checksum) around the
//! payload: model identifier and GUID (length-prefixed UTF-8), interface kind (u8), mode (u8), time,
//! start time (f64), stop time (u8 flag + f64), model ready (u8), the variable values (u32 count, then
//! per value a type tag and its payload), and the model's own bytes (u32 length + bytes).

use super::instance::{Instance, Kind};
use super::Api;
use crate::envelope::{self, EnvelopeError, Format};
use crate::units::variables::{Value, VarType};
use crate::units::UnitInfo;

/// 4: in the saved-data envelope (its checksum over the payload); 3 had its own header, the checksum
/// over everything before it; 2 had bincode 1.x in the model's bytes.
pub const VERSION: u32 = 4;
const FORMAT: Format = Format { magic: b"PFMUSTAT", version: VERSION };

/// What a saved state holds.
pub struct StateRecord {
    pub kind: u8,
    pub mode: u8,
    pub time: f64,
    pub start_time: f64,
    pub stop_time: Option<f64>,
    pub model_ready: bool,
    pub values: Vec<Value>,
    pub model: Vec<u8>,
}

pub fn write(inst: &Instance) -> Result<Vec<u8>, String> {
    let mut b = Vec::with_capacity(4096);
    put_str(&mut b, inst.unit.model_identifier)?;
    put_str(&mut b, &inst.token())?;
    b.push(if inst.kind == Kind::ModelExchange { 0 } else { 1 });
    b.push(inst.mode as u8);
    b.extend_from_slice(&inst.time.to_le_bytes());
    b.extend_from_slice(&inst.start_time.to_le_bytes());
    b.push(u8::from(inst.stop_time.is_some()));
    b.extend_from_slice(&inst.stop_time.unwrap_or(0.0).to_le_bytes());
    b.push(u8::from(inst.model_ready()));
    b.extend_from_slice(&length(inst.values.len(), "value count")?.to_le_bytes());
    for v in &inst.values {
        match v {
            Value::Real(x) => {
                b.push(0);
                b.extend_from_slice(&x.to_le_bytes());
            }
            Value::Integer(i) => {
                b.push(1);
                b.extend_from_slice(&i.to_le_bytes());
            }
            Value::Boolean(x) => {
                b.push(2);
                b.push(u8::from(*x));
            }
            Value::String(s) => {
                b.push(3);
                put_str(&mut b, s)?;
            }
        }
    }
    let model = inst.model.save().map_err(|e| e.to_string())?;
    b.extend_from_slice(&length(model.len(), "model state")?.to_le_bytes());
    b.extend_from_slice(&model);
    Ok(envelope::seal(FORMAT, &b))
}

fn put_str(b: &mut Vec<u8>, s: &str) -> Result<(), String> {
    b.extend_from_slice(&length(s.len(), "string")?.to_le_bytes());
    b.extend_from_slice(s.as_bytes());
    Ok(())
}

/// A length as the format's u32, refused (not truncated) beyond it.
fn length(n: usize, what: &str) -> Result<u32, String> {
    u32::try_from(n).map_err(|_| format!("{what} of {n} bytes or entries is beyond the format's 4 GiB limit"))
}

/// A bounds-checked reader: every read says what it wanted when the bytes run out.
struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl<'a> Reader<'a> {
    fn take(&mut self, n: usize, what: &str) -> Result<&'a [u8], String> {
        let end = self.at.checked_add(n).filter(|&e| e <= self.bytes.len());
        match end {
            Some(end) => {
                let s = &self.bytes[self.at..end];
                self.at = end;
                Ok(s)
            }
            None => Err(format!("truncated: {what} needs {n} bytes at offset {}, only {} left", self.at, self.bytes.len() - self.at)),
        }
    }
    fn u8(&mut self, what: &str) -> Result<u8, String> {
        Ok(self.take(1, what)?[0])
    }
    fn u32(&mut self, what: &str) -> Result<u32, String> {
        Ok(u32::from_le_bytes(self.take(4, what)?.try_into().expect("4 bytes")))
    }
    fn f64(&mut self, what: &str) -> Result<f64, String> {
        Ok(f64::from_le_bytes(self.take(8, what)?.try_into().expect("8 bytes")))
    }
    fn string(&mut self, what: &str) -> Result<String, String> {
        let n = self.u32(what)? as usize;
        let raw = self.take(n, what)?;
        String::from_utf8(raw.to_vec()).map_err(|_| format!("{what} is not UTF-8"))
    }
}

/// Reads a saved state for `unit` made through `api`, refusing anything that is not exactly what `write`
/// makes for it (a state of the FMI 2.0 unit carries its GUID, one of the FMI 3.0 unit its
/// instantiationToken: neither restores into the other).
pub fn read(unit: &UnitInfo, api: Api, bytes: &[u8]) -> Result<StateRecord, String> {
    let body = envelope::open(FORMAT, bytes).map_err(|e| match e {
        EnvelopeError::NotThisKind(_) => "not a powderfmu FMU state (wrong magic bytes or too short)".to_string(),
        EnvelopeError::Version { found: 2, .. } => format!("format version 2 (its model part in bincode, from powderfmu before postcard replaced it); this FMU reads version {VERSION}: save the state again with this FMU"),
        EnvelopeError::Version { found: 3, .. } => format!("format version 3 (from powderfmu before the saved-data envelope); this FMU reads version {VERSION}: save the state again with this FMU"),
        EnvelopeError::Version { found, .. } => format!("format version {found}; this FMU reads version {VERSION}"),
        other => other.to_string(),
    })?;
    let mut r = Reader { bytes: body, at: 0 };
    let id = r.string("model identifier")?;
    let guid = r.string("GUID")?;
    let token = api.token(unit);
    if id != unit.model_identifier || guid != token {
        return Err(format!("saved by {id} {guid}, not by this unit {} {token}", unit.model_identifier));
    }
    let kind = r.u8("interface kind")?;
    let mode = r.u8("mode")?;
    let time = r.f64("time")?;
    let start_time = r.f64("start time")?;
    let has_stop = r.u8("stop time flag")? != 0;
    let stop = r.f64("stop time")?;
    let model_ready = r.u8("model flag")? != 0;
    let n = r.u32("value count")? as usize;
    if n != unit.variables.len() {
        return Err(format!("{n} values, but this unit has {} variables", unit.variables.len()));
    }
    let mut values = Vec::with_capacity(n);
    for v in &unit.variables {
        let tag = r.u8("value type")?;
        let value = match (tag, v.var_type) {
            (0, VarType::Real) => Value::Real(r.f64(&v.name)?),
            (1, VarType::Integer) => Value::Integer(i32::from_le_bytes(r.take(4, &v.name)?.try_into().expect("4 bytes"))),
            (2, VarType::Boolean) => Value::Boolean(r.u8(&v.name)? != 0),
            (3, VarType::String) => Value::String(r.string(&v.name)?),
            _ => return Err(format!("value of `{}` has type tag {tag}, not {}", v.name, v.var_type.xml_name())),
        };
        values.push(value);
    }
    let m = r.u32("model state length")? as usize;
    let model = r.take(m, "model state")?.to_vec();
    if r.at != body.len() {
        return Err(format!("{} bytes left over after the model state", body.len() - r.at));
    }
    Ok(StateRecord { kind, mode, time, start_time, stop_time: has_stop.then_some(stop), model_ready, values, model })
}
