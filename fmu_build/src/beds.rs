//! The bed BallIndentation ships: the seed's bed, prepared once (`beds/README.md` says how and how long)
//! and kept in the repository, since preparing it takes hours. Packaging reads it, checks its checksum
//! and that it was made with the scene the unit's parameters start from, and refuses it otherwise.

use powderfmu::bed::{file, BedScene};
use powderfmu::units::ball_indentation::{DEFAULT_BED_SCENE, QUARTER_BED_SCENE, QUARTER_REPLICAS, SHIPPED_BED, SHIPPED_QUARTER_BED};
use powderfmu::units::unconfined_compression::{SHIPPED_SPECIMEN, SPECIMEN_REPLICAS, SPECIMEN_SCENE};
use serde_json::Value;
use std::path::Path;

/// The bytes of the shipped bed file, refused if unreadable or made with a scene other than
/// `DEFAULT_BED_SCENE` (the first differing key is named).
pub fn shipped(root: &Path) -> Result<Vec<u8>, String> {
    shipped_bed(root, SHIPPED_BED, DEFAULT_BED_SCENE)
}

/// The bytes of the shipped quarter bed (`fidelity = quarter`), checked against `QUARTER_BED_SCENE`.
pub fn shipped_quarter(root: &Path) -> Result<Vec<u8>, String> {
    shipped_bed(root, SHIPPED_QUARTER_BED, QUARTER_BED_SCENE)
}

/// The quarter beds `replicas` adds (resource name, bytes), each checked against its own scene.
pub fn shipped_quarter_replicas(root: &Path) -> Result<Vec<(&'static str, Vec<u8>)>, String> {
    QUARTER_REPLICAS.iter().map(|&(name, scene, bed)| Ok((name, shipped_bed(root, bed, scene)?))).collect()
}

/// The bytes of the specimen UnconfinedCompression ships, checked against `SPECIMEN_SCENE`.
pub fn shipped_specimen(root: &Path) -> Result<Vec<u8>, String> {
    shipped_bed(root, SHIPPED_SPECIMEN, SPECIMEN_SCENE)
}

/// The specimens `replicas` adds (resource name, bytes), each checked against its own scene.
pub fn shipped_specimen_replicas(root: &Path) -> Result<Vec<(&'static str, Vec<u8>)>, String> {
    SPECIMEN_REPLICAS.iter().map(|&(name, scene, bed)| Ok((name, shipped_bed(root, bed, scene)?))).collect()
}

fn shipped_bed(root: &Path, bed: &str, scene: &str) -> Result<Vec<u8>, String> {
    let path = root.join(bed);
    let bytes =
        std::fs::read(&path).map_err(|e| format!("cannot read the shipped bed {}: {e} (beds/README.md says how to prepare it)", path.display()))?;
    let bed = file::decode(&bytes).map_err(|e| format!("the shipped bed {}: {e}", path.display()))?;
    let theirs = BedScene::from_stored_json(&bed.scene).map_err(|e| format!("the shipped bed {}: its scene: {e}", path.display()))?;
    let ours = BedScene::from_json(scene).map_err(|e| format!("the unit's bed scene: {e}"))?;
    if let Some(key) = first_difference("", &ours.to_json(), &theirs.to_json()) {
        return Err(format!(
            "the shipped bed {} was not made with the unit's bed scene: `{key}` differs; prepare it again from that scene (beds/README.md)",
            path.display()
        ));
    }
    Ok(bytes)
}

/// The path of the first key whose values differ, ignoring what does not change the bed (`threads`:
/// results differ by round-off only; `comment`).
fn first_difference(at: &str, a: &Value, b: &Value) -> Option<String> {
    powderfmu::bed::scene_difference(at, a, b, &["threads", "comment"])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_shipped_bed_is_the_units_bed() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("the workspace root");
        let bytes = shipped(root).expect("the shipped bed is accepted");
        assert!(bytes.len() > 1_000_000, "the seed's bed of 29000 spheres");
        let quarter = shipped_quarter(root).expect("the shipped quarter bed is accepted");
        let (bed, scene) = file::load(&root.join(SHIPPED_QUARTER_BED), Some(1)).unwrap();
        assert_eq!((scene.die_sector, bed.particles().len()), (0.25, 7250));
        assert!(quarter.len() < bytes.len() / 2);
        shipped_specimen(root).expect("the shipped compression specimen is accepted");
        let (specimen, scene) = file::load(&root.join(SHIPPED_SPECIMEN), Some(1)).unwrap();
        assert_eq!((specimen.particles().len(), scene.consolidation_stress), (4000, 10e3));
    }

    /// Each replica differs from `first_scene` in its fill seed only, every seed is its own, and each bed
    /// holds `particles` spheres.
    fn assert_fills(first_scene: &str, replicas: &[(&str, Vec<u8>)], scenes: &[(&str, &str, &str)], particles: usize) {
        let first = BedScene::from_json(first_scene).unwrap().to_json();
        let mut seeds = vec![first["seed"].clone()];
        for ((name, bytes), (_, scene, _)) in replicas.iter().zip(scenes) {
            let scene = BedScene::from_json(scene).unwrap().to_json();
            assert_eq!(first_difference("", &first, &scene).as_deref(), Some("seed"), "{name}: only the fill seed differs");
            seeds.push(scene["seed"].clone());
            let (engine, _) = powderfmu::bed::AnyEngine::from_file(&file::decode(bytes).unwrap(), Some(1)).unwrap();
            assert_eq!(engine.particles().len(), particles, "{name}");
        }
        seeds.sort_by_key(|s| s.to_string());
        seeds.dedup();
        assert_eq!(seeds.len(), 1 + scenes.len(), "every bed its own fill seed");
    }

    #[test]
    fn the_replica_beds_are_the_quarter_prepared_again_with_other_seeds() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("the workspace root");
        let replicas = shipped_quarter_replicas(root).expect("the replica beds are accepted");
        assert_fills(QUARTER_BED_SCENE, &replicas, &QUARTER_REPLICAS, 7250);
    }

    #[test]
    fn the_replica_specimens_are_the_specimen_prepared_again_with_other_seeds() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("the workspace root");
        let replicas = shipped_specimen_replicas(root).expect("the replica specimens are accepted");
        assert_fills(SPECIMEN_SCENE, &replicas, &SPECIMEN_REPLICAS, 4000);
        for (name, bytes) in &replicas {
            let (_, scene) = powderfmu::bed::AnyEngine::from_file(&file::decode(bytes).unwrap(), Some(1)).unwrap();
            assert_eq!(scene.consolidation_stress, 10e3, "{name}");
        }
    }

    #[test]
    fn a_bed_of_another_scene_or_a_damaged_one_is_refused() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("the workspace root");
        let mut bed = file::decode(&std::fs::read(root.join(SHIPPED_BED)).unwrap()).unwrap();
        let other = std::env::temp_dir().join(format!("powderfmu-beds-{}", std::process::id()));
        std::fs::create_dir_all(other.join("beds")).unwrap();
        bed.scene = bed.scene.replace("\"friction_coefficient\":0.15", "\"friction_coefficient\":0.3");
        std::fs::write(other.join(SHIPPED_BED), file::encode(&bed).unwrap()).unwrap();
        let e = shipped(&other).unwrap_err();
        assert!(e.contains("`particle_particle.friction_coefficient` differs"), "{e}");
        let bytes = std::fs::read(root.join(SHIPPED_BED)).unwrap();
        std::fs::write(other.join(SHIPPED_BED), &bytes[..bytes.len() / 2]).unwrap();
        assert!(shipped(&other).is_err());
        std::fs::remove_dir_all(&other).unwrap();
    }
}
