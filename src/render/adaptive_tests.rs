use super::*;

fn adaptive(threshold: f32, min_samples: u32) -> Adaptive {
    Adaptive {
        threshold,
        min_samples,
    }
}

#[test]
fn uniform_passes_double_up_to_the_target() {
    assert_eq!(pass_ends(1, None, Progression::Doubling), vec![1]);
    assert_eq!(pass_ends(6, None, Progression::Doubling), vec![1, 2, 4, 6]);
    assert_eq!(pass_ends(8, None, Progression::Doubling), vec![1, 2, 4, 8]);
    // The doubling saturates instead of wrapping to 0 and looping.
    let ends = pass_ends(u32::MAX, None, Progression::Doubling);
    assert_eq!(ends.len(), 33);
    assert_eq!(*ends.last().unwrap(), u32::MAX);
    assert_eq!(
        pass_ends(3_000_000_000, None, Progression::Doubling).len(),
        33
    );
}

#[test]
fn batch_passes_are_whole_runs_after_the_first_sample() {
    let runs = Progression::Runs;
    assert_eq!(pass_ends(1, None, runs), vec![1]);
    assert_eq!(pass_ends(6, None, runs), vec![1, 6]);
    assert_eq!(pass_ends(64, None, runs), vec![1, BATCH, 32, 64]);
    assert_eq!(pass_ends(100, None, runs), vec![1, 16, 32, 64, 100]);
    let ends = pass_ends(u32::MAX, None, runs);
    assert_eq!(ends.len(), 30);
    assert!(ends.windows(2).all(|w| w[0] < w[1]));
    assert_eq!(*ends.last().unwrap(), u32::MAX);
    // Every pass after the first starts on a run's boundary where the
    // target allows it.
    assert!(ends[1..ends.len() - 1].iter().all(|e| e % BATCH == 0));
    // An adaptive render's decisions end passes as they do when doubling.
    let a = adaptive(0.01, 16);
    assert_eq!(
        pass_ends(64, Some(&a), runs),
        [
            vec![1],
            pass_ends(64, Some(&a), Progression::Doubling)[4..].to_vec()
        ]
        .concat()
    );
    assert_eq!(
        pass_ends(12, Some(&adaptive(0.01, 5)), runs),
        vec![1, 6, 10, 12]
    );
}

#[test]
fn a_slow_first_pass_turns_runs_into_doubling() {
    let (fast, slow) = (Duration::from_millis(1900), Duration::from_millis(2100));
    let runs = Progression::Runs;
    assert_eq!(runs.after_pass(1, fast), runs);
    assert_eq!(runs.after_pass(1, slow), Progression::Doubling);
    // Only the first pass decides; a doubling render stays one.
    assert_eq!(runs.after_pass(16, Duration::from_secs(100)), runs);
    let doubling = Progression::Doubling;
    assert_eq!(doubling.after_pass(1, fast), doubling);
}

#[test]
fn adaptive_passes_double_to_the_first_decision_then_end_at_each() {
    let a = adaptive(0.01, 16);
    let ends = pass_ends(64, Some(&a), Progression::Doubling);
    assert_eq!(
        ends,
        vec![1, 2, 4, 8, 16, 20, 24, 28, 32, 36, 40, 44, 48, 54, 60, 64]
    );
    for &e in &ends[4..ends.len() - 1] {
        assert!(is_decision(e, &a), "{e}");
        assert_eq!(e % 2, 0, "both halves hold as many samples");
    }
    for e in [1, 2, 4, 8, 15, 17, 22, 64] {
        assert!(!is_decision(e, &a), "{e}");
    }
    // An odd minimum is made even; below it no pixel is decided on.
    let odd = adaptive(0.01, 5);
    assert_eq!(
        pass_ends(12, Some(&odd), Progression::Doubling),
        vec![1, 2, 4, 6, 10, 12]
    );
    assert!(!is_decision(4, &odd) && is_decision(6, &odd));
    // Fewer samples than the first decision: the uniform passes.
    assert_eq!(
        pass_ends(8, Some(&a), Progression::Doubling),
        pass_ends(8, None, Progression::Doubling)
    );
}

#[test]
fn adaptive_passes_stay_few_at_the_largest_counts() {
    let each = [Progression::Doubling, Progression::Runs];
    let cases = [2, 16, 1000, 999_999, 1_000_000].map(|min| each.map(|p| (min, p)));
    for (min, progression) in cases.into_iter().flatten() {
        let ends = pass_ends(1_000_000, Some(&adaptive(0.01, min)), progression);
        assert!(ends.len() < 140, "{min}: {} passes", ends.len());
        assert!(ends.windows(2).all(|w| w[0] < w[1]), "{min}: increasing");
        assert_eq!(*ends.last().unwrap(), 1_000_000);
    }
    for progression in each {
        let saturated = pass_ends(u32::MAX, Some(&adaptive(0.01, 1_000_000)), progression);
        assert!(saturated.windows(2).all(|w| w[0] < w[1]));
        assert_eq!(*saturated.last().unwrap(), u32::MAX);
    }
}

#[test]
fn the_error_compares_the_half_films() {
    // Even samples 2, odd samples 4 (two each): means 2 and 4 per channel;
    // Σ_c |2 − 4| / 2 = 3 over √(3·3) = 3.
    let sum = DVec3::splat(12.0);
    let odd = DVec3::splat(8.0);
    assert!((error(sum, odd, 4) - 3.0 / (1e-4 + 3.0)).abs() < 1e-12);
    // Halves that agree: no noise; a black pixel: none either.
    assert_eq!(error(DVec3::splat(8.0), DVec3::splat(4.0), 4), 0.0);
    assert_eq!(error(DVec3::ZERO, DVec3::ZERO, 16), 0.0);
    // One sample has no odd half to compare.
    assert_eq!(error(DVec3::ONE, DVec3::ZERO, 1), f64::INFINITY);
    // The same relative difference is larger noise on a brighter pixel
    // (by the square root of the brightness).
    let dim = error(DVec3::splat(1.2), DVec3::splat(0.8), 4);
    let bright = error(DVec3::splat(120.0), DVec3::splat(80.0), 4);
    assert!((bright / dim - 10.0).abs() < 1e-3, "{dim} {bright}");
}

/// A `w`×`h` adaptive film at `count` samples, every pixel converged
/// (halves agree) but those in `noisy`.
fn film(w: u32, h: u32, count: u32, noisy: &[(u32, u32)]) -> Film {
    let mut f = Film::new(w, h, 0).with_halves();
    f.count.fill(count);
    f.sum.fill(DVec3::splat(count as f64));
    let halves = f.halves.as_mut().unwrap();
    halves.odd.fill(DVec3::splat((count / 2) as f64));
    for &(x, y) in noisy {
        halves.odd[(y * w + x) as usize] = DVec3::ZERO;
    }
    f
}

fn stopped_map(f: &Film) -> String {
    let h = f.halves.as_ref().unwrap();
    (0..f.height as usize)
        .map(|y| {
            (0..f.width as usize)
                .map(|x| {
                    if h.stopped[y * f.width as usize + x] {
                        '.'
                    } else {
                        '#'
                    }
                })
                .collect::<String>()
        })
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn a_noisy_pixel_keeps_its_window_and_their_neighbours_sampling() {
    // A noisy pixel raises the noise of the 3×3 windows around it; those
    // pixels keep their neighbours going: a 5×5 block samples on.
    let mut f = film(9, 7, 16, &[(2, 2), (8, 6)]);
    let stopped = decide(&mut f, 16, 0.01);
    assert_eq!(
        stopped_map(&f),
        "#####....
#####....
#####....
#####....
#####.###
......###
......###",
    );
    assert_eq!(stopped, 63 - 34);
    // Deciding again changes nothing; the counts are untouched.
    assert_eq!(decide(&mut f, 16, 0.01), 0);
    assert!(f.count.iter().all(|&c| c == 16));
    // Stopped pixels do not keep their neighbours going: once the noisy
    // pixels converge, the rest stop at the next decision.
    let halves = f.halves.as_mut().unwrap();
    halves.odd.fill(DVec3::splat(10.0));
    f.count.fill(20);
    f.sum.fill(DVec3::splat(20.0));
    decide(&mut f, 20, 0.01);
    assert_eq!(f.stopped_share(), Some(1.0));
    assert_eq!(f.least_active(), None);
}

#[test]
fn one_low_reading_does_not_stop_a_noisy_region() {
    // Every pixel noisy (error 0.1), but one whose halves happen to agree:
    // its window's mean is still 8/9 of the noise, and it samples on.
    let mut f = Film::new(5, 5, 0).with_halves();
    f.count.fill(16);
    f.sum.fill(DVec3::splat(16.0));
    let halves = f.halves.as_mut().unwrap();
    // Even mean 1.1, odd mean 0.9 per channel: Σ|0.2|/2 / √3 ≈ 0.17.
    halves.odd.fill(DVec3::splat(0.9 * 8.0));
    halves.odd[12] = DVec3::splat(8.0);
    assert!(error(f.sum[0], f.halves.as_ref().unwrap().odd[0], 16) > 0.15);
    assert_eq!(decide(&mut f, 16, 0.1), 0);
}

#[test]
fn a_pixel_is_judged_by_its_windows_mean_not_its_own_reading() {
    // Every pixel at noise ≈ 0.17 but the centre, which reads 0 by chance.
    // Judged alone the centre would be below 0.16 and kept only by its
    // neighbours; judged by windows, the nine windows that hold it read
    // 8/9 · 0.17 ≈ 0.15 < 0.16: the centre and those around it stop.
    let noisy = |t: f32| {
        let mut f = Film::new(7, 7, 0).with_halves();
        f.count.fill(16);
        f.sum.fill(DVec3::splat(16.0));
        let halves = f.halves.as_mut().unwrap();
        halves.odd.fill(DVec3::splat(0.9 * 8.0));
        halves.odd[24] = DVec3::splat(8.0);
        decide(&mut f, 16, t);
        f
    };
    let f = noisy(0.16);
    assert!(
        f.stopped(24),
        "the centre's window reads below the threshold"
    );
    assert!(!f.stopped(0), "a corner's window holds no low reading");
    // Below the windows' noise, nothing stops.
    assert_eq!(noisy(0.1).stopped_share(), Some(0.0));
}

#[test]
fn only_pixels_at_the_decision_count_are_decided_on() {
    // A film resumed mid-pass: pixel (2, 0) went on to 20 samples, the
    // others wait at 16. Its noise at 16 is unknown: its window and their
    // neighbours sample on.
    let mut f = film(6, 1, 16, &[]);
    f.count[2] = 20;
    decide(&mut f, 16, 0.01);
    assert_eq!(stopped_map(&f), "#####.");
    assert_eq!(f.least_active(), Some(16));
    assert_eq!(f.active_pixels(), 5);
}

#[test]
fn a_film_without_halves_is_never_decided_on() {
    let mut f = Film::new(3, 3, 0);
    f.count.fill(16);
    assert_eq!(decide(&mut f, 16, 1.0), 0);
    assert_eq!((f.stopped_share(), f.least_active()), (None, Some(16)));
}
