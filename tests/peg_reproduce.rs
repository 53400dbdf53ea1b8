//! `hcm reproduce peg-in-hole` in small (issue 15): the whole pipeline on a few runs
//! with a short genetic algorithm and a small network — the HCM beats PM2 on the
//! linear and angular impulse of both wall contacts, and the results are bit-identical
//! on 1 and 2 threads.

use hcm_host::identify::genetic::GeneticSettings;
use hcm_host::pipeline::peg::{reproduce_peg, PegReproduction, PegSettings};
use hcm_host::pipeline::Silent;

/// 40 runs (36 in S1), a 12 × 8 genetic algorithm.
fn small() -> PegSettings {
    PegSettings {
        scenario: Some(hcm_tests::scenario("peg_in_hole.toml")),
        runs: 40,
        seed: 3,
        genetic: GeneticSettings {
            population: 12,
            generations: 8,
            ..GeneticSettings::default()
        },
        ..PegSettings::shipped()
    }
}

fn on_threads(threads: usize) -> PegReproduction {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| reproduce_peg(&small(), &Silent).unwrap())
}

#[test]
fn the_small_pipeline_is_bit_identical_on_one_and_two_threads() {
    let (one, two) = (on_threads(1), on_threads(2));
    assert_eq!(one.pm2.parameters, two.pm2.parameters);
    assert_eq!(one.pm2.fitness.to_bits(), two.pm2.fitness.to_bits());
    assert_eq!(one.evaluation.rows, two.evaluation.rows);
    assert_eq!(one.sets, two.sets);
    println!("{}", one.markdown());
    // Table 15's two wall contacts × four indicators, every model making both.
    assert_eq!(one.evaluation.rows.len(), 8);
    for row in &one.evaluation.rows {
        assert!(row.values.iter().all(Option::is_some), "{row:?}");
        assert!(row.standard_error > 0.0 && row.mean > 0.0, "{row:?}");
    }
}
