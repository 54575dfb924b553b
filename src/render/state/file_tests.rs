use super::*;
use crate::render::state::info::tests::info;
use glam::Vec3;

#[test]
fn a_state_round_trips_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("s.exr");
    let mut film = Film::new(3, 2, 3);
    for (i, (s, n)) in film.sum.iter_mut().zip(&mut film.count).enumerate() {
        *n = i as u32 % 4;
        *s = DVec3::new(0.1 * i as f64, 1.0 / 3.0, 1e25) * *n as f64;
    }
    write_state(&path, &film, &info()).unwrap();
    let (back, back_info) = read_state(&path).unwrap();
    assert_eq!(back, film);
    assert_eq!(back_info, info());
    // The image part is what an EXR reader sees first.
    let (w, h, px) = crate::output::read_exr(&path).unwrap();
    assert_eq!((w, h, px[1]), (3, 2, film.pixel(1)));
}

/// The description of an adaptive render's state.
fn adaptive_info() -> StateInfo {
    let mut settings = crate::ir::settings::Settings::default();
    settings.adaptive = Some(crate::ir::settings::Adaptive {
        threshold: 0.01,
        min_samples: 16,
    });
    StateInfo {
        settings: crate::render::state::sample_settings(&settings),
        samples: 64,
        pass: crate::render::state::Pass::WHOLE,
        ..info()
    }
}

#[test]
fn an_adaptive_state_keeps_its_halves_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("s.exr");
    let mut film = Film::new(3, 2, 0).with_halves();
    let halves = film.halves.as_mut().unwrap();
    for i in 0..6 {
        film.count[i] = 16 + i as u32;
        film.sum[i] = DVec3::new(0.1 * i as f64, 1.0 / 3.0, 7.0);
        halves.odd[i] = DVec3::new(1.0 / 7.0, i as f64, 2.5);
        halves.stopped[i] = i % 2 == 1;
    }
    let adaptive = adaptive_info();
    assert!(adaptive.adaptive() && !info().adaptive());
    write_state(&path, &film, &adaptive).unwrap();
    let (back, back_info) = read_state(&path).unwrap();
    assert_eq!(back, film);
    assert_eq!(back_info, adaptive);
    assert_eq!(bytes_per_pixel(&adaptive), bytes_per_pixel(&info()) + 28);
    // Not a part: merging it is refused before its pixels are read.
    let mut total = Film::new(3, 2, 0);
    assert!(add_state(&path, &mut total)
        .unwrap_err()
        .contains("adaptive"));
}

#[test]
fn halves_no_render_makes_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("s.exr");
    let mut film = Film::new(1, 1, 0).with_halves();
    film.count[0] = 2;
    film.halves.as_mut().unwrap().odd[0] = DVec3::new(f64::INFINITY, 0.0, 0.0);
    write_state(&path, &film, &adaptive_info()).unwrap();
    assert!(read_state(&path).unwrap_err().contains("not finite"));
    film.halves.as_mut().unwrap().odd[0] = DVec3::splat(1e31);
    write_state(&path, &film, &adaptive_info()).unwrap();
    assert!(read_state(&path).unwrap_err().contains("no render makes"));
}

#[test]
fn sums_no_render_makes_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("s.exr");
    let mut film = Film::new(1, 1, 0);
    film.sum[0] = DVec3::splat(1.0);
    write_state(&path, &film, &info()).unwrap();
    assert!(
        read_state(&path).unwrap_err().contains("no render makes"),
        "a sum without samples"
    );
    film.count[0] = 1;
    film.sum[0] = DVec3::splat(1e31);
    write_state(&path, &film, &info()).unwrap();
    assert!(read_state(&path).is_err(), "a sum past the largest sample");
    film.sum[0] = DVec3::new(f64::NAN, 0.0, 0.0);
    write_state(&path, &film, &info()).unwrap();
    assert!(read_state(&path).unwrap_err().contains("not finite"));
}

#[test]
fn a_plain_image_or_garbage_is_no_state() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("plain.exr");
    crate::output::write_image(&path, (2, 2), |_| Vec3::ONE, 0.0).unwrap();
    assert!(read_state(&path).unwrap_err().contains("no render state"));
    std::fs::write(&path, b"not an exr").unwrap();
    assert!(read_state(&path).unwrap_err().contains("not an OpenEXR"));
}

#[test]
fn compressed_or_truncated_states_are_refused_from_their_headers() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("s.exr");
    let mut film = Film::new(256, 128, 3);
    film.count.fill(1);
    let zip = exr::prelude::Encoding::SMALL_LOSSLESS;
    write_state_encoded(&path, &film, &info(), zip).unwrap();
    let small = std::fs::metadata(&path).unwrap().len();
    assert!(
        small < bytes_per_pixel(&info()) * 256 * 128,
        "{small} bytes: shorter than declared"
    );
    for why in [
        read_state(&path).unwrap_err(),
        read_state_bytes(&std::fs::read(&path).unwrap()).unwrap_err(),
    ] {
        assert!(why.contains("compressed"), "{why}");
    }
    write_state(&path, &film, &info()).unwrap();
    let whole = std::fs::read(&path).unwrap();
    std::fs::write(&path, &whole[..whole.len() / 2]).unwrap();
    let why = read_state(&path).unwrap_err();
    assert!(
        why.contains("too short") && why.contains("256×128"),
        "{why}"
    );
    assert!(read_state_info(&path).is_err(), "the description alone too");
    assert_eq!(
        held_state(&path),
        HeldState::State,
        "still named a state by its headers"
    );
}

#[test]
fn a_state_adds_into_a_film_as_it_is_read() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("s.exr");
    let mut film = Film::new(5, 3, 3);
    for (i, (s, n)) in film.sum.iter_mut().zip(&mut film.count).enumerate() {
        *n = 1 + i as u32 % 2;
        *s = DVec3::splat(i as f64 + 0.25);
    }
    write_state(&path, &film, &info()).unwrap();
    let mut total = film.clone();
    assert_eq!(add_state(&path, &mut total).unwrap(), (info(), 1));
    for i in 0..15 {
        assert_eq!(total.sum[i], film.sum[i] * 2.0);
        assert_eq!(total.count[i], film.count[i] * 2);
    }
    let mut other = Film::new(3, 5, 0);
    assert!(add_state(&path, &mut other)
        .unwrap_err()
        .contains("size differs"));
}

#[test]
fn only_regular_files_are_opened() {
    let dir = tempfile::tempdir().unwrap();
    assert!(read_state(dir.path())
        .unwrap_err()
        .contains("not a regular file"));
    let fifo = dir.path().join("pipe.exr");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    if made.is_ok_and(|s| s.success()) {
        // Opening a FIFO to read would wait for a writer forever.
        assert!(read_state(&fifo)
            .unwrap_err()
            .contains("not a regular file"));
        assert_eq!(held_state(&fifo), HeldState::Absent);
    }
}

#[test]
fn what_a_file_holds_is_told_from_its_first_bytes_and_headers() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("s.exr");
    assert_eq!(held_state(&path), HeldState::Absent);
    std::fs::write(&path, b"not an exr").unwrap();
    assert!(matches!(held_state(&path), HeldState::Other(why) if why.contains("not an OpenEXR")));
    assert!(refuse_to_replace(&path, Some(false)).is_ok());
    crate::output::write_image(&path, (2, 2), |_| Vec3::ONE, 0.0).unwrap();
    assert!(matches!(held_state(&path), HeldState::Other(why) if why.contains("without")));
    let mut film = Film::new(4, 4, 2);
    film.count.fill(2);
    write_state(&path, &film, &info()).unwrap();
    assert_eq!(held_state(&path), HeldState::State);
    // The headers' first attribute declares a size past the file's end.
    let mut bytes = std::fs::read(&path).unwrap();
    let name_end = 8 + bytes[8..].iter().position(|&b| b == 0).unwrap();
    let type_end = name_end + 1 + bytes[name_end + 1..].iter().position(|&b| b == 0).unwrap();
    bytes[type_end + 1..type_end + 5].copy_from_slice(&u32::MAX.to_le_bytes());
    std::fs::write(&path, &bytes).unwrap();
    assert!(matches!(held_state(&path), HeldState::Damaged(_)));
    let why = refuse_to_replace(&path, Some(false)).unwrap_err();
    assert!(
        why.contains("may hold a render's samples") && why.contains("--force"),
        "{why}"
    );
    assert!(refuse_to_replace(&path, Some(true)).is_ok());
    // A command without --force (watch) does not offer it.
    let why = refuse_to_replace(&path, None).unwrap_err();
    assert!(
        why.contains("name another output") && !why.contains("--force"),
        "{why}"
    );
}

#[test]
fn a_splatting_render_s_light_film_round_trips_and_adds_up() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("s.exr");
    let mut film = Film::new(3, 2, 3);
    for (i, (s, n)) in film.sum.iter_mut().zip(&mut film.count).enumerate() {
        *n = 1 + i as u32 % 3;
        *s = DVec3::new(0.1 * i as f64, 1.0 / 3.0, 7.0);
    }
    let mut film = film.with_light();
    for (i, l) in film.light.as_mut().unwrap().sum.iter_mut().enumerate() {
        *l = DVec3::new(1.0 / (i + 1) as f64, 0.25, 1e-9 * i as f64);
    }
    let light_info = info().with_light();
    assert!(light_info.keeps_light() && !info().keeps_light());
    write_state(&path, &film, &light_info).unwrap();
    let (back, back_info) = read_state(&path).unwrap();
    assert_eq!(back, film, "sums, counts and the light film bit for bit");
    assert_eq!(back_info, light_info);
    assert_eq!(bytes_per_pixel(&light_info), bytes_per_pixel(&info()) + 24);
    // The image part shows the pixel with its splats.
    let (_, _, px) = crate::output::read_exr(&path).unwrap();
    assert_eq!(px[4], film.pixel(4));
    // Parts add up: light sums too, and the light paths are all samples.
    let mut total = Film::new(3, 2, 0);
    add_state(&path, &mut total).unwrap();
    add_state(&path, &mut total).unwrap();
    let light = total.light.as_ref().unwrap();
    assert_eq!(light.sum[1], film.light.as_ref().unwrap().sum[1] * 2.0);
    assert_eq!(light.paths, 2 * film.total_samples());
    // A light part whose sums no render makes is refused.
    film.light.as_mut().unwrap().sum[0] = DVec3::new(-1.0, 0.0, 0.0);
    write_state(&path, &film, &light_info).unwrap();
    assert!(read_state(&path).unwrap_err().contains("light part"));
    // Nor one that would show a pixel past the largest sample (the fuzzer's
    // find: an infinite f32 pixel).
    film.light.as_mut().unwrap().sum[0] = DVec3::new(1e35, 0.0, 0.0);
    write_state(&path, &film, &light_info).unwrap();
    assert!(read_state(&path).unwrap_err().contains("light part"));
    // Cut short in its light part: refused, whatever the cut.
    film.light.as_mut().unwrap().sum[0] = DVec3::ZERO;
    write_state(&path, &film, &light_info).unwrap();
    let whole = std::fs::read(&path).unwrap();
    for cut in [whole.len() - 8, whole.len() - 100, whole.len() * 3 / 4] {
        assert!(read_state_bytes(&whole[..cut]).is_err(), "cut at {cut}");
    }
    // A state said to keep a light film that has none is no state of it.
    let plain = dir.path().join("plain.exr");
    let mut without = film.clone();
    without.light = None;
    write_state(&plain, &without, &info()).unwrap();
    let bytes = std::fs::read(&plain).unwrap();
    assert!(read_state_bytes(&bytes).is_ok());
}
