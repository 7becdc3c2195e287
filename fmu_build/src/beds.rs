//! The prepared beds the FMUs ship: prepared once from their scene with the bed engine and kept under
//! `target/beds/`, named by a hash of the scene text, so that a changed scene prepares a new bed and
//! an unchanged one is not prepared again.

use powderfmu::bed::{file, prepare, BedScene};
use std::path::Path;
use std::time::Instant;

/// The bytes of the bed file of `scene` (JSON text), prepared now if not already under `target/beds`.
pub fn prepared(scene: &[u8], target: &Path) -> Result<Vec<u8>, String> {
    let hash = powderfmu::units::fnv1a64(scene, 0xcbf2_9ce4_8422_2325);
    let path = target.join("beds").join(format!("{hash:016x}.pfbed"));
    if let Ok(bytes) = std::fs::read(&path) {
        if file::decode(&bytes).is_ok() {
            return Ok(bytes);
        }
    }
    let text = std::str::from_utf8(scene).map_err(|_| "the bed scene is not UTF-8".to_string())?;
    let bed_scene = BedScene::from_json(text).map_err(|e| format!("bed scene: {e}"))?;
    println!("fmu_build: preparing the bed of BallIndentation ({} spheres; once, kept in {})", bed_scene.particle_count, path.display());
    let started = Instant::now();
    let mut last = "";
    let (engine, _) = prepare::prepare(&bed_scene, &mut |p| {
        if p.phase != last {
            println!("fmu_build:   {} (t = {:.3e} s, {:.0} s elapsed)", p.phase, p.time, started.elapsed().as_secs_f64());
            last = p.phase;
        }
    })
    .map_err(|e| format!("preparing the bed: {e}"))?;
    let bytes = file::encode(&engine.to_file(&bed_scene));
    std::fs::create_dir_all(path.parent().expect("a parent")).map_err(|e| format!("cannot create {}: {e}", path.display()))?;
    file::write_atomic(&path, &bytes).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    println!("fmu_build: bed prepared in {:.0} s ({} bytes)", started.elapsed().as_secs_f64(), bytes.len());
    Ok(bytes)
}
