//! Texture features on the objects, their SIFT-like detection and
//! localisation in each view, and the matches between the views: correct
//! matches of features seen in both, and mismatches between feature
//! locations (no uniform points).

use super::params::HopefParams;
use super::truth::{MatchSource, ObjectTruth};
use super::world::{blocks, Camera, Face, Shape};
use crate::synthetic::uniform;
use crate::DatasetError;
use nalgebra::Vector3;
use rand::seq::SliceRandom;
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Beta, Distribution, Poisson, StandardNormal};

/// A texture feature fixed on an object's surface.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Site {
    /// Position in the object's frame.
    pub local: Vector3<f64>,
    /// Outward unit normal in the object's frame.
    pub normal: Vector3<f64>,
    /// Keypoint scale in pixels.
    pub scale: f64,
}

/// An object of the scene: its solid, poses and texture density, and its
/// texture features.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Object {
    /// Solid, poses in views 1 and 2, density.
    pub truth: ObjectTruth,
    /// The features.
    pub sites: Vec<Site>,
}

/// A feature detected in one view, at its observed pixel.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Keypoint {
    object: usize,
    site: usize,
    pixel: [f64; 2],
}

/// One putative match, before labelling.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Match {
    /// Pixel in image 1.
    pub p1: [f64; 2],
    /// Pixel in image 2.
    pub p2: [f64; 2],
    /// What the match really is.
    pub source: MatchSource,
    /// Descriptor distance ratio `d1 / d2` (below the ratio test).
    pub ratio: f64,
}

/// A Poisson count of mean `lambda` (0 when `lambda` is not positive).
fn poisson(rng: &mut ChaCha8Rng, lambda: f64) -> usize {
    Poisson::new(lambda).map_or(0, |p| p.sample(rng) as usize)
}

/// A keypoint scale `s_min · 2^u`, `u` exponential with rate `ln(decay)`
/// truncated to `[0, max_octaves]` (inverse CDF).
fn keypoint_scale(rng: &mut ChaCha8Rng, params: &HopefParams) -> f64 {
    let rate = params.octave_decay.ln();
    let tail = (-rate * params.max_octaves).exp();
    let u = -(1.0 - rng.gen::<f64>() * (1.0 - tail)).ln() / rate;
    params.keypoint_scale_px * u.exp2()
}

/// The features of an object with `density` per unit²: on each textured
/// face, Poisson(`density × factor × area`) uniform points, `factor`
/// uniform in `face_texture`.
pub(crate) fn draw_sites(
    rng: &mut ChaCha8Rng,
    params: &HopefParams,
    shape: &Shape,
    density: f64,
) -> Vec<Site> {
    let mut sites = Vec::new();
    for (face, area) in shape.faces() {
        let factor = uniform(rng, params.face_texture);
        let count = poisson(rng, density * factor * area);
        sites.extend((0..count).map(|_| site(rng, params, &face)));
    }
    sites
}

fn site(rng: &mut ChaCha8Rng, params: &HopefParams, face: &Face) -> Site {
    let (local, normal) = face.sample(rng);
    Site {
        local,
        normal,
        scale: keypoint_scale(rng, params),
    }
}

/// The projection of site `site` of object `j` in `view` and the cosine
/// between its normal and the line of sight, when it faces the camera, is
/// in front of it and no other object hides it.
fn visible(
    camera: &Camera,
    objects: &[Object],
    j: usize,
    site: &Site,
    view: usize,
) -> Option<([f64; 2], f64)> {
    let pose = &objects[j].truth.poses[view];
    let x = pose.object_to_world(&site.local);
    let normal = pose.rotation() * site.normal;
    let to_camera = camera.centre - x;
    let cos = normal.dot(&to_camera) / to_camera.norm();
    if cos <= 0.0 {
        return None;
    }
    let pixel = camera.project(&x)?;
    let hidden = objects.iter().enumerate().any(|(i, o)| {
        let other = &o.truth;
        i != j && blocks(&other.shape, &other.poses[view], &camera.centre, &x, 1e-9)
    });
    (!hidden).then_some((pixel, cos))
}

/// Detects each visible site in `view` with probability `repeatability`
/// times the grazing ramp, at its projection plus `keypoint_offset_px` plus
/// Gaussian noise of σ = `localisation × scale` per coordinate; keypoints
/// outside the image are lost.
fn detect(
    rng: &mut ChaCha8Rng,
    params: &HopefParams,
    camera: &Camera,
    objects: &[Object],
    view: usize,
) -> Vec<Keypoint> {
    let [g0, g1] = params.grazing_cos;
    let mut out = Vec::new();
    for (j, object) in objects.iter().enumerate() {
        for (s, site) in object.sites.iter().enumerate() {
            let Some((pixel, cos)) = visible(camera, objects, j, site, view) else {
                continue;
            };
            let ramp = ((cos - g0) / (g1 - g0)).clamp(0.0, 1.0);
            if rng.gen::<f64>() >= params.repeatability * ramp {
                continue;
            }
            let sigma = params.localisation * site.scale;
            let noise: [f64; 2] = std::array::from_fn(|_| {
                let z: f64 = StandardNormal.sample(rng);
                z * sigma
            });
            let observed = std::array::from_fn(|a| pixel[a] + params.keypoint_offset_px + noise[a]);
            if camera.inside(observed) {
                out.push(Keypoint {
                    object: j,
                    site: s,
                    pixel: observed,
                });
            }
        }
    }
    out
}

/// Beta(a, b) scaled to `[0, ratio_test]`.
fn ratio_sampler(field: &'static str, [a, b]: [f64; 2]) -> Result<Beta<f64>, DatasetError> {
    Beta::new(a, b).map_err(|e| DatasetError::InvalidParams {
        field,
        problem: e.to_string(),
    })
}

/// The matches of a scene: every site detected in both views is matched to
/// itself with probability `match_rate`; then a share `q` (uniform in
/// `mismatch_share`) of the final matches are mismatches, each pairing an
/// image-1 keypoint without a correct match with an image-2 keypoint of
/// another site — of the same object with probability
/// `same_object_mismatch`, else of any object. Fewer mismatches when there
/// are not enough unmatched image-1 keypoints.
pub(crate) fn draw_matches(
    rng: &mut ChaCha8Rng,
    params: &HopefParams,
    camera: &Camera,
    objects: &[Object],
) -> Result<Vec<Match>, DatasetError> {
    let correct_ratio = ratio_sampler("ratio_beta_correct", params.ratio_beta_correct)?;
    let wrong_ratio = ratio_sampler("ratio_beta_mismatch", params.ratio_beta_mismatch)?;
    let view1 = detect(rng, params, camera, objects, 0);
    let view2 = detect(rng, params, camera, objects, 1);
    let in_view2: std::collections::HashMap<(usize, usize), usize> = view2
        .iter()
        .enumerate()
        .map(|(i, k)| ((k.object, k.site), i))
        .collect();

    let mut matches = Vec::new();
    let mut unmatched = Vec::new();
    for k1 in &view1 {
        match in_view2.get(&(k1.object, k1.site)) {
            Some(&i2) if rng.gen::<f64>() < params.match_rate => matches.push(Match {
                p1: k1.pixel,
                p2: view2[i2].pixel,
                source: MatchSource::Correct { object: k1.object },
                ratio: params.ratio_test * correct_ratio.sample(rng),
            }),
            _ => unmatched.push(*k1),
        }
    }

    let q = uniform(rng, params.mismatch_share);
    let wanted = (q * matches.len() as f64 / (1.0 - q)).round() as usize;
    let count = wanted.min(unmatched.len());
    let (chosen, _) = unmatched.partial_shuffle(rng, count);
    let mismatches = draw_mismatches(rng, params, chosen, &view2, objects.len(), &wrong_ratio);
    matches.extend(mismatches);
    Ok(matches)
}

/// A mismatch for each image-1 keypoint in `chosen`: paired with an
/// image-2 keypoint of another feature, of the same object with probability
/// `same_object_mismatch`, else of any of the `objects`, its ratio drawn
/// from `ratio`. A keypoint whose pool holds only its own feature gets none.
fn draw_mismatches(
    rng: &mut ChaCha8Rng,
    params: &HopefParams,
    chosen: &[Keypoint],
    view2: &[Keypoint],
    objects: usize,
    ratio: &Beta<f64>,
) -> Vec<Match> {
    let mut by_object: Vec<Vec<usize>> = vec![Vec::new(); objects];
    for (i, k) in view2.iter().enumerate() {
        by_object[k.object].push(i);
    }
    let everyone: Vec<usize> = (0..view2.len()).collect();
    let mut out = Vec::with_capacity(chosen.len());
    for k1 in chosen {
        let pool = if rng.gen::<f64>() < params.same_object_mismatch {
            &by_object[k1.object]
        } else {
            &everyone
        };
        // Its own feature would make a correct match.
        let own = |i: usize| (view2[i].object, view2[i].site) == (k1.object, k1.site);
        if pool.iter().all(|&i| own(i)) {
            continue;
        }
        let i2 = loop {
            let i = pool[rng.gen_range(0..pool.len())];
            if !own(i) {
                break i;
            }
        };
        out.push(Match {
            p1: k1.pixel,
            p2: view2[i2].pixel,
            source: MatchSource::Mismatch {
                object1: k1.object,
                object2: view2[i2].object,
            },
            ratio: params.ratio_test * ratio.sample(rng),
        });
    }
    out
}
