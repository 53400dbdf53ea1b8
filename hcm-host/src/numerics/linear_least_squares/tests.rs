use super::*;

fn relative(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

/// Five noisy points of a straight line, solved by hand: Σ1 = 5, Σt = 10, Σt² = 30,
/// Σy = 10.5, Σty = 30.8; c1 = (5·30.8 − 10·10.5)/(5·30 − 10²) = 49/50 = 0.98,
/// c0 = (10.5 − 0.98·10)/5 = 0.14; residuals −0.04, 0.14, −0.18, 0.10, −0.02.
const LINE: [(f64, f64); 5] = [
    (0.0, 0.1),
    (1.0, 1.26),
    (2.0, 1.92),
    (3.0, 3.18),
    (4.0, 4.04),
];

fn line_fit(covariance: Option<Covariance>) -> LinearFit {
    Reduction::from_rows(LINE.len(), 2, 1, |i, row, target| {
        row[0] = 1.0;
        row[1] = LINE[i].0;
        target[0] = LINE[i].1;
    })
    .unwrap()
    .solve(0, covariance)
    .unwrap()
}

#[test]
fn recovers_exact_coefficients_across_ten_orders_of_magnitude() {
    let x = [2.5e9, -3.0e-4, 7.0];
    let regressors = |i: usize, out: &mut [f64]| {
        let t = i as f64 / 50.0;
        out[0] = 1e-8 * (1.0 + t);
        out[1] = 1e3 * (t * t - 0.3);
        out[2] = (3.0 * t).sin();
    };
    let fit = linear_least_squares(200, 3, |i, out| {
        regressors(i, out);
        out.iter().zip(x).map(|(a, x)| a * x).sum()
    })
    .unwrap();
    assert_eq!(fit.rank, 3);
    for (found, expected) in fit.coefficients.iter().zip(x) {
        assert!(
            relative(*found, expected) < 1e-10,
            "{found} vs {expected} ({:e})",
            relative(*found, expected)
        );
    }
    assert!(fit.residual_sum_of_squares < 1e-20, "{fit:?}");
}

#[test]
fn matches_the_normal_equations_on_noisy_data() {
    let fit = linear_least_squares(LINE.len(), 2, |i, out| {
        out[0] = 1.0;
        out[1] = LINE[i].0;
        LINE[i].1
    })
    .unwrap();
    assert_eq!(fit.rank, 2);
    assert!((fit.coefficients[0] - 0.14).abs() < 1e-13, "{fit:?}");
    assert!((fit.coefficients[1] - 0.98).abs() < 1e-13, "{fit:?}");
    let rss = [0.04_f64, 0.14, 0.18, 0.10, 0.02]
        .iter()
        .map(|r| r * r)
        .sum::<f64>();
    assert!((fit.residual_sum_of_squares - rss).abs() < 1e-13, "{fit:?}");
    assert_eq!(fit.covariance, None, "not asked");
}

#[test]
fn straight_line_covariance_is_the_closed_form() {
    // XᵀX = [[5, 10], [10, 30]], det 50: (XᵀX)⁻¹ = [[30, −10], [−10, 5]]/50; RSS = 0.064
    // over n − p = 3 degrees of freedom.
    let unscaled = [[30.0 / 50.0, -10.0 / 50.0], [-10.0 / 50.0, 5.0 / 50.0]];
    let variance = 0.064 / 3.0;
    for (kind, scale) in [
        (Covariance::Unscaled, 1.0),
        (Covariance::ResidualVariance, variance),
    ] {
        let fit = line_fit(Some(kind));
        let covariance = fit.covariance.clone().expect("full rank, n > p");
        for a in 0..2 {
            for b in 0..2 {
                let expected = scale * unscaled[a][b];
                assert!(
                    relative(covariance[a][b], expected) < 1e-12,
                    "{kind:?} [{a}][{b}]: {} vs {expected}",
                    covariance[a][b]
                );
            }
        }
    }
    // Standard errors of the textbook formulas: SE(c1) = σ̂/√Σ(t − t̄)², Σ(t − t̄)² = 10.
    let fit = line_fit(Some(Covariance::ResidualVariance));
    let slope_error = fit.covariance.unwrap()[1][1].sqrt();
    assert!(relative(slope_error, (variance / 10.0).sqrt()) < 1e-12);
}

#[test]
fn identical_columns_are_reported_rank_deficient() {
    // y = 3·t + 2, with t given twice (second copy in other units) beside a constant.
    let fit = linear_least_squares(20, 3, |i, out| {
        let t = i as f64;
        out[0] = t;
        out[1] = 1.0;
        out[2] = 1e6 * t;
        3.0 * t + 2.0
    })
    .unwrap();
    assert_eq!(fit.rank, 2, "{fit:?}");
    assert!(fit.coefficients.iter().all(|c| c.is_finite()));
    // The two copies share the slope; one of them is 0.
    let slope = fit.coefficients[0] + 1e6 * fit.coefficients[2];
    assert!((slope - 3.0).abs() < 1e-10, "{fit:?}");
    assert!(fit.coefficients[0] == 0.0 || fit.coefficients[2] == 0.0);
    assert!((fit.coefficients[1] - 2.0).abs() < 1e-10, "{fit:?}");
    assert!(fit.residual_sum_of_squares < 1e-18, "{fit:?}");

    let exact_copies = linear_least_squares(10, 2, |i, out| {
        out[0] = i as f64;
        out[1] = i as f64;
        i as f64
    })
    .unwrap();
    assert_eq!(exact_copies.rank, 1);
    assert!((exact_copies.coefficients.iter().sum::<f64>() - 1.0).abs() < 1e-12);

    let zero_column = linear_least_squares(10, 2, |i, out| {
        out[0] = i as f64;
        2.0 * i as f64
    })
    .unwrap();
    assert_eq!(zero_column.rank, 1);
    assert_eq!(zero_column.coefficients[1], 0.0);
    assert!((zero_column.coefficients[0] - 2.0).abs() < 1e-13);
}

#[test]
fn a_rank_deficient_problem_has_no_covariance() {
    // Two copies of t: the fit exists (basic solution) but their split does not.
    for kind in [Covariance::Unscaled, Covariance::ResidualVariance] {
        let fit = Reduction::from_rows(10, 2, 1, |i, row, target| {
            row[0] = i as f64;
            row[1] = 2.0 * i as f64;
            target[0] = 1.0 + i as f64;
        })
        .unwrap()
        .solve(0, Some(kind))
        .unwrap();
        assert_eq!(fit.rank, 1);
        assert_eq!(fit.covariance, None, "{kind:?}");
    }
    // n = p: the scaled covariance has no degree of freedom, the unscaled one exists.
    let square = |kind| {
        Reduction::from_rows(2, 2, 1, |i, row, target| {
            row[0] = 1.0;
            row[1] = i as f64;
            target[0] = 3.0;
        })
        .unwrap()
        .solve(0, Some(kind))
        .unwrap()
        .covariance
    };
    assert_eq!(square(Covariance::ResidualVariance), None);
    assert!(square(Covariance::Unscaled).is_some());
}

#[test]
fn blocks_stacks_and_column_subsets_give_the_whole_problem() {
    // 3000 rows (several blocks), two targets; a deterministic well-spread design.
    let spread = |i: usize| (i as f64 * 0.618_033_988_749_894_9).fract();
    let regressors = |i: usize, row: &mut [f64]| {
        let t = spread(i);
        row[0] = 1.0;
        row[1] = t;
        row[2] = (7.0 * t).cos();
    };
    let targets = |i: usize, row: &[f64], out: &mut [f64]| {
        let noise = spread(3 * i + 1) - 0.5;
        out[0] = 2.0 - row[1] + 0.5 * row[2] + 0.01 * noise;
        out[1] = -row[2] + 0.02 * noise;
    };
    let rows = 3000;
    let whole = Reduction::from_rows(rows, 3, 2, |i, row, out| {
        regressors(i, row);
        targets(i, row, out);
    })
    .unwrap();
    assert_eq!((whole.rows(), whole.triangle_rows()), (rows, 3));
    // Two parts reduced apart, then their triangles stacked as rows of a new problem.
    let part = |range: std::ops::Range<usize>| {
        Reduction::from_rows(range.len(), 3, 2, |i, row, out| {
            regressors(range.start + i, row);
            targets(range.start + i, row, out);
        })
        .unwrap()
    };
    let parts = [part(0..1234), part(1234..rows)];
    for target in 0..2 {
        let expected = whole.solve(target, None).unwrap();
        let stacked = linear_least_squares(6, 3, |i, row| {
            let (p, k) = (&parts[i / 3], i % 3);
            for (j, r) in row.iter_mut().enumerate() {
                *r = p.triangle(k, j);
            }
            p.projected_target(k, target)
        })
        .unwrap();
        let orthogonal: f64 = parts
            .iter()
            .map(|p| p.orthogonal_sum_of_squares(target))
            .sum();
        for (a, b) in stacked.coefficients.iter().zip(&expected.coefficients) {
            assert!((a - b).abs() < 1e-12, "{stacked:?} vs {expected:?}");
        }
        let rss = stacked.residual_sum_of_squares + orthogonal;
        assert!(relative(rss, expected.residual_sum_of_squares) < 1e-9);
        // The same against a direct row-by-row solve of this target alone.
        let direct = linear_least_squares(rows, 3, |i, row| {
            regressors(i, row);
            let mut out = [0.0; 2];
            targets(i, row, &mut out);
            out[target]
        })
        .unwrap();
        for (a, b) in direct.coefficients.iter().zip(&expected.coefficients) {
            assert!((a - b).abs() < 1e-12, "{direct:?} vs {expected:?}");
        }
    }
    // Columns {0, 2} of the triangle: the fit of columns {0, 2} of A.
    let subset = linear_least_squares(3, 2, |k, row| {
        row[0] = whole.triangle(k, 0);
        row[1] = whole.triangle(k, 2);
        whole.projected_target(k, 1)
    })
    .unwrap();
    let direct = linear_least_squares(rows, 2, |i, row| {
        let mut full = [0.0; 3];
        regressors(i, &mut full);
        let mut out = [0.0; 2];
        targets(i, &full, &mut out);
        (row[0], row[1]) = (full[0], full[2]);
        out[1]
    })
    .unwrap();
    for (a, b) in subset.coefficients.iter().zip(&direct.coefficients) {
        assert!((a - b).abs() < 1e-12, "{subset:?} vs {direct:?}");
    }
    let rss = subset.residual_sum_of_squares + whole.orthogonal_sum_of_squares(1);
    assert!(relative(rss, direct.residual_sum_of_squares) < 1e-9);
}

#[test]
fn non_finite_entries_name_their_row() {
    let error = linear_least_squares(10, 2, |i, out| {
        out[0] = 1.0;
        out[1] = if i == 7 { f64::NAN } else { i as f64 };
        1.0
    })
    .unwrap_err();
    assert!(matches!(
        error,
        LinearLeastSquaresError::NonFiniteEntry { row: 7 }
    ));
    assert!(error.to_string().contains("row 7"), "{error}");

    let error = linear_least_squares(4, 2, |i, out| {
        out[0] = 1.0;
        if i == 3 {
            f64::INFINITY
        } else {
            1.0
        }
    })
    .unwrap_err();
    assert!(matches!(
        error,
        LinearLeastSquaresError::NonFiniteEntry { row: 3 }
    ));
}

#[test]
fn too_few_rows_or_none_are_errors() {
    let error = linear_least_squares(2, 3, |_, _| 0.0).unwrap_err();
    assert!(matches!(
        error,
        LinearLeastSquaresError::TooFewRows {
            rows: 2,
            unknowns: 3
        }
    ));
    assert!(matches!(
        linear_least_squares(0, 1, |_, _| 0.0),
        Err(LinearLeastSquaresError::NoRows)
    ));
    assert!(matches!(
        linear_least_squares(3, 0, |_, _| 0.0),
        Err(LinearLeastSquaresError::NoUnknowns)
    ));
    let empty = Reduction::from_rows(0, 2, 1, |_, _, _| {}).unwrap();
    assert_eq!(empty.triangle_rows(), 0);
    assert!(matches!(
        empty.solve(1, None),
        Err(LinearLeastSquaresError::NoSuchTarget {
            target: 1,
            targets: 1
        })
    ));
}

#[test]
fn ridge_is_the_penalised_normal_equations() {
    // (XᵀX + μI)·x = Xᵀy for the straight line: XᵀX = [[5, 10], [10, 30]], Xᵀy = [10.5,
    // 30.8]; with μ = 2: [[7, 10], [10, 32]]·x = [10.5, 30.8], det 124.
    let reduction = Reduction::from_rows(LINE.len(), 2, 1, |i, row, target| {
        row[0] = 1.0;
        row[1] = LINE[i].0;
        target[0] = LINE[i].1;
    })
    .unwrap();
    let fit = reduction.solve_ridge(0, 2.0).unwrap();
    let expected = [
        (32.0 * 10.5 - 10.0 * 30.8) / 124.0,
        (7.0 * 30.8 - 10.0 * 10.5) / 124.0,
    ];
    for (a, b) in fit.coefficients.iter().zip(expected) {
        assert!(relative(*a, b) < 1e-13, "{fit:?} vs {expected:?}");
    }
    let rss: f64 = LINE
        .iter()
        .map(|(t, y)| (expected[0] + expected[1] * t - y).powi(2))
        .sum();
    assert!(
        relative(fit.residual_sum_of_squares, rss) < 1e-12,
        "{fit:?}"
    );
    // μ = 0 is the plain solve; two identical columns share the weight under a ridge.
    let plain = reduction.solve_ridge(0, 0.0).unwrap();
    let exact = reduction.solve(0, None).unwrap();
    for (a, b) in plain.coefficients.iter().zip(&exact.coefficients) {
        assert!((a - b).abs() < 1e-13);
    }
    let twins = Reduction::from_rows(10, 2, 1, |i, row, target| {
        (row[0], row[1]) = (i as f64, i as f64);
        target[0] = 2.0 * i as f64;
    })
    .unwrap()
    .solve_ridge(0, 1e-9)
    .unwrap();
    assert!((twins.coefficients[0] - 1.0).abs() < 1e-9, "{twins:?}");
    assert!((twins.coefficients[1] - 1.0).abs() < 1e-9, "{twins:?}");
}

#[test]
fn columns_give_the_reduction_of_rows_bit_for_bit() {
    // Rows past two blocks (1024 each), columns ten orders of magnitude apart.
    for rows in [3, 7, 1024, 2500] {
        let column = |j: usize| -> Vec<f64> {
            (0..rows)
                .map(|i| {
                    let x = (i as f64 * 0.37 + j as f64).sin();
                    x * 10f64.powi(j as i32 * 2 - 5)
                })
                .collect()
        };
        let columns: Vec<Vec<f64>> = (0..5).map(column).collect();
        let target: Vec<f64> = (0..rows).map(|i| (i as f64 * 0.11).cos() + 0.3).collect();
        let by_rows = Reduction::from_rows(rows, 5, 1, |i, row, out| {
            for (value, c) in row.iter_mut().zip(&columns) {
                *value = c[i];
            }
            out[0] = target[i];
        })
        .unwrap();
        let slices: Vec<&[f64]> = columns.iter().map(Vec::as_slice).collect();
        let by_columns = Reduction::from_columns(&slices, &target).unwrap();
        assert_eq!(by_rows.rows(), by_columns.rows());
        assert_eq!(by_rows.triangle_rows(), by_columns.triangle_rows());
        for i in 0..by_rows.triangle_rows() {
            for j in 0..5 {
                let (a, b) = (by_rows.triangle(i, j), by_columns.triangle(i, j));
                assert_eq!(a.to_bits(), b.to_bits(), "{rows} rows: R[{i}, {j}]");
            }
            let (a, b) = (
                by_rows.projected_target(i, 0),
                by_columns.projected_target(i, 0),
            );
            assert_eq!(a.to_bits(), b.to_bits(), "{rows} rows: Qᵀb[{i}]");
        }
        let (a, b) = (
            by_rows.orthogonal_sum_of_squares(0),
            by_columns.orthogonal_sum_of_squares(0),
        );
        assert_eq!(a.to_bits(), b.to_bits(), "{rows} rows: the rest");
    }
    // The first non-finite row is named, as row by row.
    let mut column = vec![1.0; 50];
    column[31] = f64::NAN;
    let mut target = vec![2.0; 50];
    target[17] = f64::INFINITY;
    assert_eq!(
        Reduction::from_columns(&[&column], &target).unwrap_err(),
        LinearLeastSquaresError::NonFiniteEntry { row: 17 }
    );
    assert_eq!(
        Reduction::from_columns(&[], &target).unwrap_err(),
        LinearLeastSquaresError::NoUnknowns
    );
}
