//! The bed file: a prepared bed, compact and versioned.
//!
//! The payload (`codec`, postcard, of `BedFile`) in the saved-data envelope (`envelope`: the magic
//! `PFBED\0\0\0`, the format version, the length, the checksum). The reader checks each in turn and
//! names what is wrong. The writer writes a temporary file beside the target and renames it, so a bed
//! file is either whole or absent.

use super::any::{AnyEngine, BedError};
use super::engine::{Engine, WallContacts};
use super::interaction::BedLaw;
use super::particles::Particles;
use super::scene::BedScene;
use super::walls::Wall;
use super::Vec3;
use crate::envelope::{self, EnvelopeError, Format};
use std::io::Write;
use std::path::Path;

/// A wall contact as the file keeps it: the particle, its law history, tangential spring and contact radius.
type SavedWallContact<H> = (u32, H, Vec3, f64);

/// The magic bytes that open a bed file's envelope.
pub const MAGIC: &[u8; 8] = b"PFBED\0\0\0";
/// 3: postcard payload (`codec`). 2 and 1 were bincode 1.x, which is unmaintained (RUSTSEC-2025-0141).
pub const VERSION: u32 = 3;
/// The bed file's envelope.
pub const FORMAT: Format = Format { magic: MAGIC, version: VERSION };

/// What a bed file holds.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct BedFile {
    /// The bed scene (JSON text) the bed was made with.
    pub scene: String,
    /// Simulated time when saved [s].
    pub time: f64,
    /// Centre position of each particle [m].
    pub position: Vec<Vec3>,
    /// Velocity of each particle [m/s].
    pub velocity: Vec<Vec3>,
    /// Angular velocity of each particle [rad/s].
    pub angular_velocity: Vec<Vec3>,
    /// Species (size class) of each particle; radius and mass follow from the scene.
    pub species: Vec<u16>,
    /// The walls, with their positions, velocities and forces of the last step.
    pub walls: Vec<Wall>,
    /// `codec` bytes of the particle contacts `Vec<(i, j, history, spring, contact radius)>` of the scene's law.
    pub contacts: Vec<u8>,
    /// `codec` bytes of the wall contacts `Vec<Vec<(i, history, spring, contact radius)>>`, one list per wall.
    pub wall_contacts: Vec<u8>,
    /// The forces, torques and rolling loads of the last step: a loaded bed continues exactly where it
    /// was saved (velocity Verlet's next half kick uses them).
    pub force: Vec<Vec3>,
    /// Torque on each particle in the last step [N m].
    pub torque: Vec<Vec3>,
    /// Rolling friction load of each particle in the last step, the sum of mu_r |f_n| over its contacts [N].
    pub rolling: Vec<f64>,
}

impl<L: BedLaw> Engine<L> {
    /// The contacts that remember something (history changed or spring loaded), as `codec` bytes.
    fn saved_contacts(&self) -> Result<(Vec<u8>, Vec<u8>), BedError> {
        let pairs: Vec<_> = self
            .remembering()
            .map(|(i, j, k)| {
                let (h, s, a) = self.memory.get(k);
                (i as u32, j, h, s, a)
            })
            .collect();
        let walls: Vec<Vec<SavedWallContact<L::History>>> = self
            .wall_contacts
            .iter()
            .enumerate()
            .map(|(w, wc)| {
                (0..wc.particle.len())
                    .filter(|&k| wc.memory.remembers(k, self.wall_pairs[w][self.particles.species[wc.particle[k] as usize] as usize].initial))
                    .map(|k| {
                        let (h, s, a) = wc.memory.get(k);
                        (wc.particle[k], h, s, a)
                    })
                    .collect()
            })
            .collect();
        let bytes = |what: &str, r: Result<Vec<u8>, String>| r.map_err(|e| BedError::Setup(format!("bed file: the {what} cannot be written ({e})")));
        Ok((bytes("contacts", crate::codec::to_bytes(&pairs))?, bytes("wall contacts", crate::codec::to_bytes(&walls))?))
    }

    /// Puts saved contacts back into the current lists (they are within range: they were in contact).
    fn restore_contacts(&mut self, pairs: &[u8], walls: &[u8]) -> Result<(), BedError> {
        // The near lists were built on the memory replaced here.
        self.near.valid = false;
        let pairs: Vec<(u32, u32, L::History, Vec3, f64)> =
            crate::codec::from_bytes(pairs).map_err(|e| BedError::Setup(format!("bed file: contacts unreadable ({e})")))?;
        let walls: Vec<Vec<SavedWallContact<L::History>>> =
            crate::codec::from_bytes(walls).map_err(|e| BedError::Setup(format!("bed file: wall contacts unreadable ({e})")))?;
        // A saved contact beyond the list's range (its spheres moved apart since the saving engine last
        // built its list) is put into the list: the saving engine held it until its next rebuild.
        let n = self.particles.len() as u32;
        let mut grown = self.list.insert_missing(pairs.iter().filter(|c| c.0 < c.1 && c.1 < n).map(|c| (c.0, c.1)));
        if grown {
            let slots = self.list.partner.len();
            let init = self.pairs[0].initial;
            self.memory.resize_fresh(slots, init);
        }
        for (w, list) in walls.iter().enumerate() {
            if let Some(wc) = self.wall_contacts.get_mut(w) {
                let init = self.wall_pairs[w][0].initial;
                for &(i, ..) in list {
                    if let Err(k) = wc.particle.binary_search(&i) {
                        if i < n {
                            wc.particle.insert(k, i);
                            wc.memory.insert_fresh(k, init);
                            grown = true;
                        }
                    }
                }
            }
        }
        if grown {
            // The parts over threads stay cut on the list the positions give (`Engine::rebuild`).
            self.resize_buffers();
        }
        // Every slot starts as a pair that has never touched (the engine's first force pass may have
        // loaded springs); the file then says which remember something.
        for i in 0..self.list.rows() {
            let a = self.particles.species[i] as usize;
            for k in self.list.start[i] as usize..self.list.start[i + 1] as usize {
                let b = self.particles.species[self.list.partner[k] as usize] as usize;
                let init = self.pair(a, b).initial;
                self.memory.reset(k, init);
            }
        }
        for (w, wc) in self.wall_contacts.iter_mut().enumerate() {
            for k in 0..wc.particle.len() {
                wc.memory.reset(k, self.wall_pairs[w][self.particles.species[wc.particle[k] as usize] as usize].initial);
            }
        }
        for (i, j, h, s, a) in pairs {
            if i >= n || j >= n {
                return Err(BedError::Setup(format!("bed file: contact ({i}, {j}) names a particle beyond {n}")));
            }
            let row = self.list.row(i as usize);
            let k =
                row.binary_search(&j).map_err(|_| BedError::Setup(format!("bed file: contact ({i}, {j}) is not within range of the positions")))?;
            let slot = self.list.start[i as usize] as usize + k;
            self.memory.set(slot, (h, s, a));
        }
        if walls.len() != self.wall_contacts.len() {
            return Err(BedError::Setup("bed file: wall contact lists do not match the walls".into()));
        }
        for (w, list) in walls.into_iter().enumerate() {
            let wc: &mut WallContacts<L::History> = &mut self.wall_contacts[w];
            for (i, h, s, a) in list {
                let k = wc
                    .particle
                    .binary_search(&i)
                    .map_err(|_| BedError::Setup(format!("bed file: wall contact of particle {i} is not within range")))?;
                wc.memory.set(k, (h, s, a));
            }
        }
        self.compute_forces_without_increment();
        Ok(())
    }
}

impl AnyEngine {
    /// The bed as a file holds it; an error where some part cannot be serialised.
    pub fn to_file(&self, scene: &BedScene) -> Result<BedFile, BedError> {
        with_engine!(self, e => {
            let (contacts, wall_contacts) = e.saved_contacts()?;
            Ok(BedFile {
                scene: scene.to_json().to_string(),
                time: e.time,
                position: e.particles.position.clone(),
                velocity: e.particles.velocity.clone(),
                angular_velocity: e.particles.angular_velocity.clone(),
                species: e.particles.species.clone(),
                walls: e.walls.clone(),
                contacts,
                wall_contacts,
                force: e.totals().forces(),
                torque: e.totals().torques(),
                rolling: e.totals().rolling_loads(),
            })
        })
    }

    /// Rebuilds the engine of a bed file (with `threads` threads, or the scene's).
    pub fn from_file(file: &BedFile, threads: Option<usize>) -> Result<(AnyEngine, BedScene), BedError> {
        let mut scene = BedScene::from_stored_json(&file.scene)?;
        if let Some(t) = threads {
            scene.threads = t;
        }
        let n = file.position.len();
        if file.velocity.len() != n || file.angular_velocity.len() != n || file.species.len() != n {
            return Err(BedError::Setup("bed file: particle arrays of different lengths".into()));
        }
        let sp = scene.species();
        let mut p = Particles::default();
        for k in 0..n {
            let s = file.species[k] as usize;
            let &(r, _) =
                sp.get(s).ok_or_else(|| BedError::Setup(format!("bed file: particle {k} has species {s} beyond the {} classes", sp.len())))?;
            p.push(file.position[k], r, scene.density, s as u16);
            p.velocity[k] = file.velocity[k];
            p.angular_velocity[k] = file.angular_velocity[k];
        }
        let mut e = AnyEngine::build(&scene, p, file.walls.clone())?;
        with_engine!(&mut e, inner => {
            inner.time = file.time;
            inner.restore_contacts(&file.contacts, &file.wall_contacts)?;
            if file.force.len() == n && file.torque.len() == n && file.rolling.len() == n {
                inner.set_totals(&file.force, &file.torque, &file.rolling);
                // The walls' forces of the last step too: building the engine ran a force pass of its
                // own, and a restored test must read the indenter's force it was saved with.
                for (w, saved) in inner.walls.iter_mut().zip(&file.walls) {
                    w.force = saved.force;
                }
            }
        });
        Ok((e, scene))
    }
}

/// Encodes a bed file; an error (not an empty payload) where it cannot be serialised.
pub fn encode(file: &BedFile) -> Result<Vec<u8>, BedError> {
    let payload = crate::codec::to_bytes(file).map_err(|e| BedError::Setup(format!("bed file: cannot be written ({e})")))?;
    Ok(envelope::seal(FORMAT, &payload))
}

/// Decodes a bed file, naming what is wrong with a bad one.
pub fn decode(bytes: &[u8]) -> Result<BedFile, BedError> {
    let bad = |why: String| BedError::Setup(format!("not a usable bed file: {why}"));
    let payload = envelope::open(FORMAT, bytes).map_err(|e| match e {
        EnvelopeError::Version { found: found @ (1 | 2), .. } => bad(format!(
            "format version {found} (bincode, written by powderfmu before postcard replaced it), this powderfmu reads version {VERSION}; prepare the bed again with `powderfmu bed prepare`"
        )),
        EnvelopeError::Version { found, .. } => {
            bad(format!("format version {found}, this powderfmu reads version {VERSION}; prepare the bed again with `powderfmu bed prepare`"))
        }
        other => bad(other.to_string()),
    })?;
    crate::codec::from_bytes(payload).map_err(|e| bad(format!("payload unreadable ({e})")))
}

/// Writes `bytes` to `path` atomically: a temporary file in the same folder, synced, then renamed.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    // Only a regular file (or none) is replaced by renaming: renaming onto /dev/null, a FIFO or a
    // terminal would put a regular file in its place (as root, /dev/null itself, which then fed stale
    // output to every program reading it). Those are written to directly.
    if std::fs::metadata(path).is_ok_and(|m| !m.is_file()) {
        return std::fs::OpenOptions::new().write(true).open(path)?.write_all(bytes);
    }
    let dir = path.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_else(|| "bed".into());
    let tmp = dir.join(format!(".{name}.tmp-{}", std::process::id()));
    let result = (|| {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// Saves the bed to `path` (atomically); a bed that cannot be serialised is an error before anything is written.
pub fn save(path: &Path, engine: &AnyEngine, scene: &BedScene) -> std::io::Result<()> {
    let bytes = engine.to_file(scene).and_then(|f| encode(&f)).map_err(|e| std::io::Error::new(std::io::ErrorKind::InvalidData, e.to_string()))?;
    write_atomic(path, &bytes)
}

/// Loads a bed file from `path`: the engine (with `threads` threads, or the scene's) and the scene it was made with.
pub fn load(path: &Path, threads: Option<usize>) -> Result<(AnyEngine, BedScene), BedError> {
    let bytes = std::fs::read(path).map_err(|e| BedError::Setup(format!("cannot read bed file `{}`: {e}", path.display())))?;
    AnyEngine::from_file(&decode(&bytes)?, threads)
}

#[cfg(all(test, unix))]
mod tests {
    use std::os::unix::fs::FileTypeExt;

    #[test]
    fn writing_to_dev_null_leaves_it_the_null_device() {
        let null = std::path::Path::new("/dev/null");
        assert!(std::fs::metadata(null).unwrap().file_type().is_char_device(), "/dev/null is broken before the test");
        super::write_atomic(null, b"output nobody wants").unwrap();
        assert!(std::fs::metadata(null).unwrap().file_type().is_char_device(), "write_atomic replaced /dev/null");
    }

    #[test]
    fn a_regular_file_is_replaced_whole() {
        let path = std::env::temp_dir().join(format!("powderfmu-atomic-{}", std::process::id()));
        std::fs::write(&path, b"a longer old content").unwrap();
        super::write_atomic(&path, b"new").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"new");
        std::fs::remove_file(&path).unwrap();
    }
}
