//! Malformed and unsupported GeoTIFFs: errors that name the file and the problem, and never a
//! panic on a corrupted file.

mod common;

use common::*;
use shoal::seafloor::{
    info, load, LoadOptions, SampleType, SeafloorError, TiffCompression, TiffLayout, Values,
};
use std::path::Path;

/// Writes a TIFF with the `tiff` crate directly, for files shoal's writer would not make.
fn raw_tiff(
    path: &Path,
    tags: impl FnOnce(
        &mut tiff::encoder::DirectoryEncoder<
            '_,
            &mut std::fs::File,
            tiff::encoder::TiffKindStandard,
        >,
    ),
) {
    let mut file = std::fs::File::create(path).unwrap();
    let mut enc = tiff::encoder::TiffEncoder::new(&mut file).unwrap();
    let mut image = enc
        .new_image::<tiff::encoder::colortype::Gray32Float>(4, 3)
        .unwrap();
    tags(image.encoder());
    image.write_data(&[-10.0f32; 12]).unwrap();
}

#[test]
fn malformed_or_unsupported_files_give_errors_that_name_the_file_and_the_problem() {
    use tiff::tags::Tag;
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let case = |name: &str, f: &dyn Fn(&Path)| {
        let p = d.join(name);
        f(&p);
        let err = load(&p, &LoadOptions::default()).unwrap_err().to_string();
        assert!(err.contains(name), "{err}");
        err
    };
    let plain = case("plain.tif", &|p| raw_tiff(p, |_| {}));
    assert!(
        plain.contains("ModelPixelScale (33550) and ModelTiepoint (33922) are missing"),
        "{plain}"
    );
    let no_scale = case("noscale.tif", &|p| {
        raw_tiff(p, |e| {
            e.write_tag(Tag::ModelTiepointTag, &[0.0, 0.0, 0.0, 1.0, 2.0, 0.0][..])
                .unwrap()
        })
    });
    assert!(
        no_scale.contains("ModelPixelScale (33550) is missing"),
        "{no_scale}"
    );
    let rotated = case("rotated.tif", &|p| {
        let m = [
            10.0, 2.0, 0.0, 5e5, 1.0, -10.0, 0.0, 4e6, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0,
        ];
        raw_tiff(p, |e| {
            e.write_tag(Tag::ModelTransformationTag, &m[..]).unwrap()
        })
    });
    assert!(rotated.contains("rotated or sheared"), "{rotated}");
    let gcps = case("gcps.tif", &|p| {
        raw_tiff(p, |e| {
            e.write_tag(
                Tag::ModelTiepointTag,
                &[0.0, 0.0, 0.0, 1.0, 2.0, 0.0, 3.0, 2.0, 0.0, 9.0, 1.0, 0.0][..],
            )
            .unwrap()
        })
    });
    assert!(gcps.contains("control points"), "{gcps}");
    let feet = case("feet.tif", &|p| {
        raw_tiff(p, |e| {
            e.write_tag(Tag::ModelPixelScaleTag, &[1.0, 1.0, 0.0][..])
                .unwrap();
            e.write_tag(Tag::ModelTiepointTag, &[0.0, 0.0, 0.0, 1.0, 2.0, 0.0][..])
                .unwrap();
            e.write_tag(
                Tag::GeoKeyDirectoryTag,
                &[1u16, 1, 0, 2, 1024, 0, 1, 1, 3076, 0, 1, 9002][..],
            )
            .unwrap();
        })
    });
    assert!(feet.contains("ProjLinearUnitsGeoKey = 9002"), "{feet}");
    let bad_keys = case("keys.tif", &|p| {
        raw_tiff(p, |e| {
            e.write_tag(Tag::ModelPixelScaleTag, &[1.0, 1.0, 0.0][..])
                .unwrap();
            e.write_tag(Tag::ModelTiepointTag, &[0.0, 0.0, 0.0, 1.0, 2.0, 0.0][..])
                .unwrap();
            e.write_tag(Tag::GeoKeyDirectoryTag, &[1u16, 1, 0, 5, 1024, 0, 1, 1][..])
                .unwrap();
        })
    });
    assert!(
        bad_keys.contains("GeoKeyDirectory (34735) is malformed"),
        "{bad_keys}"
    );
    let rgb = case("rgb.tif", &|p| {
        let mut file = std::fs::File::create(p).unwrap();
        let mut enc = tiff::encoder::TiffEncoder::new(&mut file).unwrap();
        enc.write_image::<tiff::encoder::colortype::RGB8>(2, 2, &[0u8; 12])
            .unwrap();
    });
    assert!(rgb.contains("single band"), "{rgb}");
    let absurd = case("absurd.tif", &|p| {
        raw_tiff(p, |e| {
            e.write_tag(Tag::ModelPixelScaleTag, &[1.0, 1.0, 0.0][..])
                .unwrap();
            e.write_tag(Tag::ModelTiepointTag, &[0.0, 0.0, 0.0, 1.0, 2.0, 0.0][..])
                .unwrap();
            e.write_tag(Tag::GdalNodata, "-99999").unwrap();
        });
        // poke a value out of range: rewrite the file with 1e6 in a pixel
        let mut bytes = std::fs::read(p).unwrap();
        let needle = (-10.0f32).to_le_bytes();
        let at = bytes.windows(4).position(|w| w == needle).unwrap();
        bytes[at..at + 4].copy_from_slice(&1e6f32.to_le_bytes());
        std::fs::write(p, bytes).unwrap();
    });
    assert!(
        absurd.contains("row 1, column 1") && absurd.contains("within ±50000"),
        "{absurd}"
    );
    let text = case("text.tif", &|p| std::fs::write(p, "not a tiff").unwrap());
    assert!(text.contains("not a readable TIFF"), "{text}");
    let nc = case("grid.nc", &|p| std::fs::write(p, "").unwrap());
    let unknown = case("grid.dem", &|p| std::fs::write(p, "").unwrap());
    if cfg!(feature = "gdal") {
        // GDAL opens anything, and says what it cannot
        for e in [&nc, &unknown] {
            assert!(e.contains("GDAL cannot open it"), "{e}");
        }
    } else {
        assert!(
            nc.contains("grid.nc") && nc.contains("cargo build --release --features gdal"),
            "{nc}"
        );
        assert!(unknown.contains("unknown grid format"), "{unknown}");
    }
    let missing = load(&d.join("nope.tif"), &LoadOptions::default()).unwrap_err();
    assert!(
        matches!(missing, SeafloorError::Io { .. }) && missing.to_string().contains("nope.tif")
    );
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(200))]
    /// Any corruption of a valid GeoTIFF (bytes overwritten, file truncated) gives a floor or
    /// an error, never a panic.
    #[test]
    fn corrupt_files_never_panic(
        edits in proptest::collection::vec((0usize..4000, proptest::prelude::any::<u8>()), 1..6),
        cut in 0usize..5000,
        tiled in proptest::prelude::any::<bool>(),
    ) {
        let dir = tempfile::tempdir().unwrap();
        let (l, z, nd) = geographic();
        let z: Vec<f64> = z.iter().map(|v| v.round()).collect();
        let layout = if tiled { TiffLayout::Tiles { size: 64 } } else { strips(TiffCompression::Deflate) };
        let p = tif(dir.path(), "c.tif", (&l, &z, &nd), &WGS84, SampleType::Int16, layout);
        let mut bytes = std::fs::read(&p).unwrap();
        let n = bytes.len();
        for (at, b) in edits {
            // aim at the header and the IFD at the end as well as the data
            let k = if at % 2 == 0 { at % n } else { n - 1 - (at % n) };
            bytes[k] = b;
        }
        if cut < 1000 {
            bytes.truncate(n.saturating_sub(cut * 37));
        }
        std::fs::write(&p, &bytes).unwrap();
        let _ = load(&p, &LoadOptions::default());
        let _ = info(&p, Values::Elevation);
    }
}
