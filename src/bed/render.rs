//! A PNG cross-section of the bed: the vertical plane through the die axis (y = 0). Each sphere the
//! plane cuts is drawn as its disc of section, coloured by its share of the vertical stress,
//! -dipole_zz / V_p (Bagi's per-particle term, 004 Eq. 5.1), on a logarithmic scale from dark blue
//! (least) to yellow (most): the force chains stand out. Die, floor and piston are drawn in grey.

use super::any::AnyEngine;

/// What was drawn: image size and the colour scale [Pa].
#[derive(Debug, Clone, Copy)]
pub struct Legend {
    /// Image width [pixels].
    pub width: u32,
    /// Image height [pixels].
    pub height: u32,
    /// Stress at the dark blue end of the scale [Pa].
    pub stress_low: f64,
    /// Stress at the yellow end of the scale, the largest drawn [Pa].
    pub stress_high: f64,
    /// Number of spheres the plane y = 0 cuts (the discs drawn).
    pub spheres_cut: usize,
}

fn colour(t: f64) -> [u8; 3] {
    // A perceptually ordered ramp: dark blue, teal, green, yellow.
    const STOPS: [[f64; 3]; 5] = [[40.0, 20.0, 90.0], [40.0, 90.0, 140.0], [30.0, 150.0, 135.0], [120.0, 200.0, 70.0], [250.0, 230.0, 40.0]];
    let t = t.clamp(0.0, 1.0) * 4.0;
    let k = (t.floor() as usize).min(3);
    let f = t - k as f64;
    let mut c = [0u8; 3];
    for q in 0..3 {
        c[q] = (STOPS[k][q] * (1.0 - f) + STOPS[k + 1][q] * f) as u8;
    }
    c
}

/// Renders the section as PNG bytes, `width` pixels across the die.
pub fn cross_section(engine: &mut AnyEngine, die_diameter: f64, width: u32) -> Result<(Vec<u8>, Legend), String> {
    let (centres, radii, walls) = {
        let p = engine.particles();
        (p.position.clone(), p.radius.clone(), engine.walls().to_vec())
    };
    let dipoles = engine.measure_dipoles();
    let top = centres.iter().zip(&radii).map(|(x, r)| x[2] + r).fold(0.0, f64::max);
    let margin = 0.05 * die_diameter;
    let (x0, x1) = (-0.5 * die_diameter - margin, 0.5 * die_diameter + margin);
    let (z0, z1) = (-margin, top + 2.0 * margin);
    let scale = width as f64 / (x1 - x0);
    let height = ((z1 - z0) * scale).ceil().max(1.0) as u32;
    let mut img = vec![255u8; (width * height * 3) as usize];
    let stress: Vec<f64> = dipoles.iter().zip(&radii).map(|(d, r)| (-d[(2, 2)] / (4.0 / 3.0 * std::f64::consts::PI * r.powi(3))).max(0.0)).collect();
    let positive: Vec<f64> = stress.iter().cloned().filter(|s| *s > 0.0).collect();
    let high = positive.iter().cloned().fold(0.0, f64::max);
    let low = positive.iter().cloned().fold(f64::INFINITY, f64::min).max(high * 1e-4);
    let mut cut = 0;
    for k in 0..centres.len() {
        let (x, r) = (centres[k], radii[k]);
        if x[1].abs() >= r {
            continue;
        }
        cut += 1;
        let rc = (r * r - x[1] * x[1]).sqrt();
        let t = if stress[k] > 0.0 && high > low { ((stress[k] / low).ln() / (high / low).ln()).clamp(0.0, 1.0) } else { 0.0 };
        let c = if stress[k] > 0.0 { colour(t) } else { [200, 200, 210] };
        let (px, pz, pr) = ((x[0] - x0) * scale, (z1 - x[2]) * scale, rc * scale);
        let (ia, ib) = (((px - pr).floor().max(0.0)) as u32, ((px + pr).ceil() as u32).min(width - 1));
        let (ja, jb) = (((pz - pr).floor().max(0.0)) as u32, ((pz + pr).ceil() as u32).min(height - 1));
        for j in ja..=jb {
            for i in ia..=ib {
                let (dx, dz) = (i as f64 + 0.5 - px, j as f64 + 0.5 - pz);
                if dx * dx + dz * dz <= pr * pr {
                    let o = ((j * width + i) * 3) as usize;
                    img[o..o + 3].copy_from_slice(&c);
                }
            }
        }
    }
    // Walls: vertical lines for the die, horizontal for the floor and piston.
    let grey = [90u8, 90, 90];
    let mut line = |i0: i64, j0: i64, i1: i64, j1: i64| {
        for j in j0.max(0)..=j1.min(height as i64 - 1) {
            for i in i0.max(0)..=i1.min(width as i64 - 1) {
                let o = ((j as u32 * width + i as u32) * 3) as usize;
                img[o..o + 3].copy_from_slice(&grey);
            }
        }
    };
    for w in &walls {
        match w.shape {
            super::walls::Shape::Cylinder { radius } => {
                for side in [-1.0, 1.0] {
                    let i = ((side * radius - x0) * scale) as i64;
                    line(i - 1, 0, i + 1, height as i64);
                }
            }
            super::walls::Shape::Plane { normal } if normal[2].abs() > 0.99 => {
                let j = ((z1 - w.position[2]) * scale) as i64;
                line(0, j - 1, width as i64, j + 1);
            }
            _ => {}
        }
    }
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, width, height);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        let mut writer = enc.write_header().map_err(|e| e.to_string())?;
        writer.write_image_data(&img).map_err(|e| e.to_string())?;
    }
    Ok((out, Legend { width, height, stress_low: low, stress_high: high, spheres_cut: cut }))
}
