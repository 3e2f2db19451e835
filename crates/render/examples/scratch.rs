#[path = "../tests/common/mod.rs"]
mod common;
use common::*;
use glam::UVec2;
use integrators::{Mis, PathSettings};
use render::technique::Transport;
use sampling::sampler::SamplerKind;
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let name = &args[1];
    let spp: u32 = args[2].parse().unwrap();
    let scene = load_file(&scenes_dir().join(name), &[], 24, 24);
    let base = mis_power(max_depth(&scene), false);
    let bsdf = PathSettings {
        sample_lights: false,
        mis: Mis::Off,
        ..base
    };
    let light = PathSettings {
        mis: Mis::Off,
        ..base
    };
    let px: Vec<u32> = args[3..].iter().map(|s| s.parse().unwrap()).collect();
    for (label, t) in [
        ("ref", reference(&scene)),
        ("bsdf", Transport::Path(bsdf)),
        ("light", Transport::Path(light)),
        ("mis", Transport::Path(base)),
    ] {
        for seed in [2] {
            let f = render(&scene, t, SamplerKind::Independent, spp, seed, label);
            println!("{label} mean {:.6}", film_mean(&f));
            for b in px.chunks(2) {
                let mut s = glam::Vec3::ZERO;
                let mut v = glam::Vec3::ZERO;
                for dy in 0..2 {
                    for dx in 0..2 {
                        let p = f.pixel(UVec2::new(b[0] + dx, b[1] + dy));
                        s += p.mean();
                        v += p.variance_of_mean();
                    }
                }
                println!("{label} {b:?}: block sum {:.5} sd {:.5}", s.x, v.x.sqrt());
            }
        }
    }
}
