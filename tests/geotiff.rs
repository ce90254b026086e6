//! Grid files: GeoTIFF and ESRI ASCII fixtures written by the crate's own writers, loaded back
//! through `seafloor::load` in every sample type, layout and sign convention; geographic grids
//! resampled onto the local frame; windows; `seafloor::info`.

mod common;

use common::*;
use shoal::seafloor::geo::LocalFrame;
use shoal::seafloor::{
    info, load, Crs, Lattice, LoadOptions, Region, SampleType, Seafloor, SeafloorError,
    TiffCompression, TiffLayout, Values,
};

#[test]
fn every_format_sample_type_and_layout_gives_the_same_floor() {
    let dir = tempfile::tempdir().unwrap();
    let (l, z, nd) = survey();
    let reference = floor_of(&l, &z, &nd);
    let asc = dir.path().join("survey.asc");
    reference.write_esri_ascii(&asc).unwrap();
    let from_asc = load(&asc, &LoadOptions::default()).unwrap();
    assert_eq!(from_asc.floor.fingerprint(), reference.fingerprint());
    assert_eq!(
        (from_asc.format.name(), from_asc.crs.to_string()),
        ("esri-ascii", "none".into())
    );
    let layouts = [
        strips(TiffCompression::None),
        strips(TiffCompression::Deflate),
        strips(TiffCompression::Lzw),
        TiffLayout::Strips {
            rows: 0,
            compression: TiffCompression::None,
        },
        TiffLayout::Tiles { size: 16 },
    ];
    let samples = [
        SampleType::Float32,
        SampleType::Float64,
        SampleType::Int16,
        SampleType::Int32,
    ];
    for (k, sample) in samples.into_iter().enumerate() {
        for (m, layout) in layouts.into_iter().enumerate() {
            let p = tif(
                dir.path(),
                &format!("s{k}_{m}.tif"),
                (&l, &z, &nd),
                &UTM,
                sample,
                layout,
            );
            let got = load(&p, &LoadOptions::default()).unwrap();
            assert_eq!(
                got.floor.fingerprint(),
                reference.fingerprint(),
                "{sample:?} {layout:?}"
            );
            assert_eq!(got.crs.to_string(), "EPSG:32631");
            assert_eq!(got.format.name(), "geotiff");
            assert!(got.warnings.is_empty(), "{:?}", got.warnings);
            // same depth at the same place, between nodes too
            for (x, y) in [(500_123.4, 4_700_300.1), (500_700.0, 4_700_500.0)] {
                assert_eq!(
                    got.floor.elevation(x, y).unwrap(),
                    from_asc.floor.elevation(x, y).unwrap()
                );
            }
        }
    }
    // NODATA hole and island are obstacles after the round trip
    let p = dir.path().join("s2_0.tif");
    let f = load(&p, &LoadOptions::default()).unwrap().floor;
    assert!(
        f.is_nodata(6, 21)
            && f.is_obstacle(l.x0 + 6.5 * l.dx, l.y0 + 21.5 * l.dy)
                .unwrap()
    );
    assert!(f
        .is_obstacle(l.x0 + 30.0 * l.dx, l.y0 + 8.0 * l.dy)
        .unwrap());
    assert_eq!(f.obstacle_counts(), (9, 25));
}

#[test]
fn float32_rounds_other_values_and_seafloor_export_is_lossless() {
    let dir = tempfile::tempdir().unwrap();
    let (l, mut z, nd) = survey();
    z.iter_mut()
        .enumerate()
        .for_each(|(k, v)| *v -= 0.123_456_789 * (k % 7) as f64);
    let reference = floor_of(&l, &z, &nd);
    let p = tif(
        dir.path(),
        "f32.tif",
        (&l, &z, &nd),
        &Crs::None,
        SampleType::Float32,
        strips(TiffCompression::Deflate),
    );
    let f = load(&p, &LoadOptions::default()).unwrap().floor;
    for j in 0..l.ny {
        for i in 0..l.nx {
            let (a, b) = (f.node(i, j), reference.node(i, j));
            assert!(
                (a - b).abs() <= b.abs() * f64::from(f32::EPSILON),
                "{a} vs {b}"
            );
        }
    }
    // Seafloor::write_geotiff picks float64 when float32 would round: bit-exact.
    let exact = dir.path().join("exact.tif");
    reference.write_geotiff(&exact, &Crs::None, None).unwrap();
    assert_eq!(
        load(&exact, &LoadOptions::default())
            .unwrap()
            .floor
            .fingerprint(),
        reference.fingerprint()
    );
    // an odd origin (no exact corner form) is written as PixelIsPoint, still exact
    let odd = Seafloor::from_nodes(
        Lattice::new(3, 2, 0.1, 0.7, 0.3, 0.3),
        vec![-1.0; 6],
        vec![false; 6],
    )
    .unwrap();
    let p = dir.path().join("odd.tif");
    odd.write_geotiff(&p, &Crs::None, None).unwrap();
    assert_eq!(load(&p, &LoadOptions::default()).unwrap().floor, odd);
}

#[test]
fn depth_grids_are_negated_and_a_wrong_convention_is_warned_about() {
    let dir = tempfile::tempdir().unwrap();
    let (l, z, nd) = survey();
    let elevation = floor_of(&l, &z, &nd);
    let depth: Vec<f64> = z.iter().map(|v| -v).collect();
    for (k, sample) in [SampleType::Int16, SampleType::Float32]
        .into_iter()
        .enumerate()
    {
        let p = tif(
            dir.path(),
            &format!("depth{k}.tif"),
            (&l, &depth, &nd),
            &UTM,
            sample,
            strips(TiffCompression::None),
        );
        let got = load(&p, &opts(Values::Depth)).unwrap();
        assert_eq!(got.floor.fingerprint(), elevation.fingerprint());
        assert!(got.warnings.is_empty());
        assert_eq!(got.values, Values::Depth);
        let wrong = load(&p, &opts(Values::Elevation)).unwrap();
        assert_eq!(wrong.warnings.len(), 1);
        let w = &wrong.warnings[0];
        assert!(w.contains("depth0.tif") || w.contains("depth1.tif"), "{w}");
        assert!(
            w.contains("are positive") && w.contains("seafloor.values = \"depth\""),
            "{w}"
        );
    }
    // elevations read as depths: the other warning
    let asc = dir.path().join("elev.asc");
    elevation.write_esri_ascii(&asc).unwrap();
    let w = load(&asc, &opts(Values::Depth)).unwrap().warnings;
    assert!(
        w.len() == 1 && w[0].contains("set seafloor.values = \"elevation\""),
        "{w:?}"
    );
    // uint16 depths (a common survey product)
    let pos: Vec<f64> = depth.iter().map(|v| v.max(0.0)).collect();
    let p = tif(
        dir.path(),
        "u16.tif",
        (&l, &pos, &nd),
        &UTM,
        SampleType::UInt16,
        TiffLayout::Tiles { size: 32 },
    );
    let f = load(&p, &opts(Values::Depth)).unwrap().floor;
    assert_eq!(f.node(0, 0), -120.0);
}

#[test]
fn projected_grids_keep_their_coordinates_and_refuse_an_origin() {
    let dir = tempfile::tempdir().unwrap();
    let (l, z, nd) = survey();
    let p = tif(
        dir.path(),
        "utm.tif",
        (&l, &z, &nd),
        &UTM,
        SampleType::Float32,
        strips(TiffCompression::None),
    );
    let got = load(&p, &LoadOptions::default()).unwrap();
    assert_eq!((got.floor.x0(), got.floor.y0()), (l.x0, l.y0));
    assert_eq!(got.origin, None);
    let err = load(
        &p,
        &LoadOptions {
            origin: Some([43.0, 3.0]),
            ..LoadOptions::default()
        },
    )
    .unwrap_err();
    let msg = err.to_string();
    assert!(
        msg.contains("utm.tif") && msg.contains("seafloor.origin") && msg.contains("EPSG:32631"),
        "{msg}"
    );
}

#[test]
fn windows_read_only_the_nodes_asked_for_and_plans_rebuild_them_exactly() {
    let dir = tempfile::tempdir().unwrap();
    let (l, z, nd) = survey();
    let whole = floor_of(&l, &z, &nd);
    for (k, layout) in [strips(TiffCompression::Lzw), TiffLayout::Tiles { size: 16 }]
        .into_iter()
        .enumerate()
    {
        let p = tif(
            dir.path(),
            &format!("w{k}.tif"),
            (&l, &z, &nd),
            &UTM,
            SampleType::Float32,
            layout,
        );
        let area = Region::Area {
            x_min: l.x0 + 100.0,
            x_max: l.x0 + 330.0,
            y_min: l.y0 + 260.0,
            y_max: l.y0 + 400.0,
        };
        let cut = load_region(&p, area).unwrap().floor;
        // one node beyond the area each side: i from 4 to 18, j from 9 to 17
        assert_eq!((cut.nx(), cut.ny()), (15, 9));
        assert_eq!((cut.x0(), cut.y0()), (l.x0 + 4.0 * l.dx, l.y0 + 9.0 * l.dy));
        for j in 0..cut.ny() {
            for i in 0..cut.nx() {
                assert_eq!(cut.node(i, j), whole.node(i + 4, j + 9));
                assert_eq!(cut.is_nodata(i, j), whole.is_nodata(i + 4, j + 9));
            }
        }
        let again = load_region(&p, nodes_of(&cut)).unwrap().floor;
        assert_eq!(again.fingerprint(), cut.fingerprint());
        // a lattice the grid does not hold
        let off = Region::Nodes {
            x0: cut.x0() + 3.0,
            y0: cut.y0(),
            nx: 4,
            ny: 4,
        };
        assert!(matches!(
            load_region(&p, off),
            Err(SeafloorError::Region { .. })
        ));
        // an area beside the grid
        let away = Region::Area {
            x_min: 0.0,
            x_max: 10.0,
            y_min: 0.0,
            y_max: 10.0,
        };
        let msg = load_region(&p, away).unwrap_err().to_string();
        assert!(
            msg.contains("does not overlap the grid") && msg.contains("[initial]"),
            "{msg}"
        );
    }
}

#[test]
fn geographic_grids_are_resampled_onto_the_local_tangent_plane() {
    let dir = tempfile::tempdir().unwrap();
    let (l, z, nd) = geographic();
    let p = tif(
        dir.path(),
        "gebco.tif",
        (&l, &z, &nd),
        &WGS84,
        SampleType::Float64,
        strips(TiffCompression::Deflate),
    );
    let got = load(&p, &LoadOptions::default()).unwrap();
    assert_eq!(got.crs.to_string(), "EPSG:4326");
    let [lat0, lon0] = got.origin.unwrap();
    assert!((lat0 - 43.05).abs() < 1e-12 && (lon0 - 5.07).abs() < 1e-12);
    let frame = LocalFrame::new(lat0, lon0).unwrap();
    let f = &got.floor;
    // native spacing at the origin: 0.001° ≈ 81.4 m east, 111.1 m north
    assert!(
        (f.dx() - 81.44).abs() < 0.05 && (f.dy() - 111.09).abs() < 0.05,
        "{f:?}"
    );
    assert_eq!(f.x0() / f.dx(), (f.x0() / f.dx()).round());
    // the frame covers the grid, less the border lines that fall outside it
    let e = f.extent();
    assert!(
        e.x_min < -5600.0 && e.x_max > 5600.0 && e.y_min < -5400.0 && e.y_max > 5400.0,
        "{e}"
    );
    let (mut checked, mut max_err) = (0, 0.0f64);
    for j in 0..f.ny() {
        for i in 0..f.nx() {
            let (x, y) = (f.x0() + i as f64 * f.dx(), f.y0() + j as f64 * f.dy());
            let [lat, lon] = frame.to_geographic(x, y).unwrap();
            let near_hole = (lon - 5.0215).abs() < 0.003 && (lat - 43.0705).abs() < 0.003;
            let near_island = (lon - 5.12).abs() < 0.003 && (lat - 43.08).abs() < 0.003;
            if near_hole || near_island {
                continue;
            }
            assert!(!f.is_nodata(i, j));
            max_err = max_err.max((f.node(i, j) - geo_depth(lat, lon)).abs());
            checked += 1;
        }
    }
    assert!(
        checked > 10_000 && max_err < 1e-9,
        "{checked} nodes, error {max_err}"
    );
    // the same depth at the same place, between nodes: a point given in degrees
    let (lat, lon) = (43.0312, 5.0456);
    let [x, y] = frame.to_local(lat, lon);
    let d = f.elevation(x, y).unwrap() - geo_depth(lat, lon);
    assert!(d.abs() < 1e-3, "{d}");
    // NODATA and land grow to every metric node whose native cell touches them
    let [hx, hy] = frame.to_local(43.0705, 5.0215);
    assert!(f.obstacle(hx, hy).unwrap() == Some(shoal::seafloor::Obstacle::Nodata));
    let [ix, iy] = frame.to_local(43.08, 5.12);
    assert!(f.elevation(ix, iy).unwrap() >= 0.0 && f.is_obstacle(ix, iy).unwrap());
    // an explicit origin moves the frame; the floor follows it
    let o = LoadOptions {
        origin: Some([43.02, 5.03]),
        ..LoadOptions::default()
    };
    let moved = load(&p, &o).unwrap();
    let [mx, my] = LocalFrame::new(43.02, 5.03).unwrap().to_local(lat, lon);
    let d = moved.floor.elevation(mx, my).unwrap() - geo_depth(lat, lon);
    assert!(d.abs() < 1e-3, "{d}");
    // an int16 copy of the same grid (rounded values) gives the same lattice
    let zi: Vec<f64> = z.iter().map(|v| v.round()).collect();
    let pi = tif(
        dir.path(),
        "gebco16.tif",
        (&l, &zi, &nd),
        &WGS84,
        SampleType::Int16,
        TiffLayout::Tiles { size: 32 },
    );
    let gi = load(&pi, &LoadOptions::default()).unwrap().floor;
    assert_eq!(gi.lattice(), f.lattice());
    // the mission window: only nodes near the start, and the recorded lattice rebuilds it
    let area = Region::Area {
        x_min: -1000.0,
        x_max: 1200.0,
        y_min: -800.0,
        y_max: 900.0,
    };
    let cut = load_region(&p, area).unwrap().floor;
    assert!(cut.nx() < 35 && cut.ny() < 25, "{cut:?}");
    let c = cut.extent();
    assert!(c.x_min <= -1000.0 && c.x_max >= 1200.0 && c.y_min <= -800.0 && c.y_max >= 900.0);
    let again = load_region(&p, nodes_of(&cut)).unwrap();
    assert_eq!(again.floor.fingerprint(), cut.fingerprint());
    for j in 0..cut.ny() {
        for i in 0..cut.nx() {
            let (x, y) = (
                cut.x0() + i as f64 * cut.dx(),
                cut.y0() + j as f64 * cut.dy(),
            );
            assert_eq!(cut.elevation(x, y).unwrap(), f.elevation(x, y).unwrap());
        }
    }
}

#[test]
fn info_reports_size_extent_crs_range_nodata_land_and_origin() {
    let dir = tempfile::tempdir().unwrap();
    let p = geographic_tif(dir.path(), "g.tif");
    let i = info(&p, Values::Elevation).unwrap();
    assert_eq!((i.native.nx, i.native.ny), (141, 101));
    assert_eq!(
        (i.nodata_nodes, i.land_nodes, i.data_nodes),
        (6, 1, 141 * 101 - 6)
    );
    let [lat, lon] = i.origin;
    assert!((lat - 43.05).abs() < 1e-12 && (lon - 5.07).abs() < 1e-12);
    let text = i.to_string();
    for needle in [
        "141 × 101 nodes",
        "EPSG:4326",
        "seafloor.origin = [43.050000, 5.070000]",
        "6 NODATA",
        "1 land",
        "longitude 5 to",
    ] {
        assert!(text.contains(needle), "{needle}:\n{text}");
    }
    let m = i.metric_extent.unwrap();
    assert!(m[0] < -5600.0 && m[1] > 5600.0, "{m:?}");
    let (lo, hi) = i.z_range.unwrap();
    assert!(lo < -150.0 && hi == 3.0);
    // a projected grid: the centre in its own metres; depths: the sign warning
    let (l, z, nd) = survey();
    let p = tif(
        dir.path(),
        "u.tif",
        (&l, &z, &nd),
        &UTM,
        SampleType::Int16,
        strips(TiffCompression::None),
    );
    let i = info(&p, Values::Depth).unwrap();
    assert_eq!(i.origin, [l.x0 + 400.0, l.y0 + 375.0]);
    assert_eq!(i.warnings.len(), 1);
    assert!(i.to_string().contains("EPSG:32631"));
}

/// The file with its PhotometricInterpretation (tag 262, a SHORT) set to `value`: its IFD
/// entry, little-endian, is found by its bytes and patched in place.
fn with_photometric(path: &std::path::Path, value: u16) {
    let mut bytes = std::fs::read(path).unwrap();
    assert_eq!(&bytes[..2], b"II", "the writer's files are little-endian");
    let entry = |v: u16| {
        let mut e = vec![0x06, 0x01, 0x03, 0x00, 0x01, 0x00, 0x00, 0x00];
        e.extend_from_slice(&v.to_le_bytes());
        e
    };
    let (from, to) = (entry(1), entry(value));
    let at = bytes
        .windows(from.len())
        .position(|w| w == from.as_slice())
        .expect("a BlackIsZero PhotometricInterpretation entry");
    bytes[at..at + to.len()].copy_from_slice(&to);
    std::fs::write(path, bytes).unwrap();
}

/// Regression (issue 13): a GeoTIFF with PhotometricInterpretation WhiteIsZero was read as
/// 1 − z (the TIFF decoder inverts brightness); elevations are data, and GDAL ignores the tag
/// for data bands. It is now read as written, and signed integers, which the decoder refuses
/// to invert, get a message that says how to rewrite the file.
#[test]
fn regression_white_is_zero_was_read_as_one_minus_z() {
    let dir = tempfile::tempdir().unwrap();
    let (l, z, nd) = survey();
    for (k, sample) in [SampleType::Float32, SampleType::Float64, SampleType::UInt16]
        .into_iter()
        .enumerate()
    {
        let values: Vec<f64> = match sample {
            // unsigned: elevations above the surface are its only valid values
            SampleType::UInt16 => z.iter().map(|v| v.abs().round()).collect(),
            _ => z.clone(),
        };
        let name = format!("w{k}.tif");
        let layout = strips(TiffCompression::None);
        let p = tif(dir.path(), &name, (&l, &values, &nd), &UTM, sample, layout);
        let black = load(&p, &LoadOptions::default()).unwrap().floor;
        with_photometric(&p, 0);
        let white = load(&p, &LoadOptions::default()).unwrap().floor;
        for (x, y) in [(500_123.4, 4_700_300.1), (500_700.0, 4_700_500.0)] {
            let (b, w) = (
                black.elevation(x, y).unwrap(),
                white.elevation(x, y).unwrap(),
            );
            assert!((b - w).abs() < 1e-3, "{sample:?}: {b} read as {w}");
        }
        assert_eq!(
            white.obstacle_counts(),
            black.obstacle_counts(),
            "{sample:?}"
        );
    }
    let p = tif(
        dir.path(),
        "w_int.tif",
        (&l, &z, &nd),
        &UTM,
        SampleType::Int16,
        strips(TiffCompression::None),
    );
    with_photometric(&p, 0);
    let e = load(&p, &LoadOptions::default()).unwrap_err().to_string();
    assert!(
        e.contains("WhiteIsZero") && e.contains("PHOTOMETRIC=MINISBLACK"),
        "{e}"
    );
}

/// Regression (issue 13): for a grid that is mostly land, the sign warning only said to set
/// values = depth; it now says the positive nodes may simply be land.
#[test]
fn regression_a_mostly_land_grid_is_not_only_called_a_depth_grid() {
    let dir = tempfile::tempdir().unwrap();
    let (l, z, nd) = survey();
    // 60 % of the data nodes above sea level: a coastal grid
    let coast: Vec<f64> = (0..z.len())
        .map(|k| if k % 5 < 3 { 10.0 } else { -50.0 })
        .collect();
    let layout = strips(TiffCompression::None);
    let p = tif(
        dir.path(),
        "coast.tif",
        (&l, &coast, &nd),
        &UTM,
        SampleType::Float32,
        layout,
    );
    let w = load(&p, &LoadOptions::default())
        .unwrap()
        .warnings
        .join("\n");
    assert!(w.contains("% of the data values are positive"), "{w}");
    assert!(w.contains("seafloor.values = \"depth\""), "{w}");
    assert!(
        w.contains("mostly land, the positive nodes are land"),
        "{w}"
    );
}

/// Regression (issue 13): `seafloor info` suggested the centre of a coastal grid as the
/// mission's origin without saying it is on land. It now names the nearest node a plan can
/// start from (water all round, clear of the cells that touch land) and how far it is; a grid
/// whose centre is open water keeps the centre.
#[test]
fn regression_info_suggests_the_nearest_water_node_for_a_land_centre() {
    let dir = tempfile::tempdir().unwrap();
    let (l, _, nd) = survey();
    // land (+10 m) west of column 24, water (−50 m) from it on: the centre (20, 15) is land
    let coast: Vec<f64> = (0..l.nx * l.ny)
        .map(|k| if k % l.nx < 24 { 10.0 } else { -50.0 })
        .collect();
    let p = tif(
        dir.path(),
        "coast.tif",
        (&l, &coast, &vec![false; nd.len()]),
        &UTM,
        SampleType::Float32,
        strips(TiffCompression::None),
    );
    let i = info(&p, Values::Elevation).unwrap();
    let ([x, y], d) = i.water_origin.expect("a water node");
    // column 24 is water but its cells touch the land of column 23: three nodes in
    assert_eq!([x, y], [l.x0 + 27.0 * l.dx, l.y0 + 15.0 * l.dy]);
    assert!((d - 140.0).abs() < 1e-9, "{d}");
    assert!(!i.centre_clear);
    let text = i.to_string();
    assert!(
        text.contains(
            "the grid centre is on land or NODATA, or next to it; the nearest node a plan can \
             start from is x = 500550.0, y = 4700387.5 m, 140 m from it"
        ),
        "{text}"
    );
    // the survey grid's centre is water: no other suggestion
    let (l, z, nd) = survey();
    let p = tif(
        dir.path(),
        "s.tif",
        (&l, &z, &nd),
        &UTM,
        SampleType::Float32,
        strips(TiffCompression::None),
    );
    assert_eq!(info(&p, Values::Elevation).unwrap().water_origin, None);
}
