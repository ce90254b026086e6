use super::*;

fn geo(epsg: Option<u16>) -> Crs {
    Crs::Geographic { epsg }
}

fn proj(epsg: u16) -> Crs {
    Crs::Projected {
        epsg: Some(epsg),
        citation: None,
    }
}

#[test]
fn declarations_are_epsg_codes_of_a_known_kind() {
    assert_eq!(parse_crs("EPSG:4326"), Ok(geo(Some(4326))));
    assert_eq!(parse_crs(" epsg: 4258 "), Ok(geo(Some(4258))));
    assert_eq!(parse_crs("EPSG:7844"), Ok(geo(Some(7844))));
    assert_eq!(parse_crs("EPSG:32756"), Ok(proj(32756)));
    assert_eq!(parse_crs("EPSG:3857"), Ok(proj(3857)));
    for (bad, says) in [
        ("WGS84", "expected \"EPSG:<code>\""),
        ("EPSG:", "expected \"EPSG:<code>\""),
        ("EPSG:0", "expected \"EPSG:<code>\""),
        ("EPSG:-4326", "expected \"EPSG:<code>\""),
        ("EPSG:4326.5", "expected \"EPSG:<code>\""),
        ("", "expected \"EPSG:<code>\""),
        ("EPSG:102100", "not supported"),
        ("EPSG:32767", "not supported"),
        ("EPSG:4978", "geocentric"),
    ] {
        let e = parse_crs(bad).unwrap_err();
        assert!(e.contains(says), "{bad}: {e}");
    }
}

const ESRI_WGS84: &str = "GEOGCS[\"GCS_WGS_1984\",DATUM[\"D_WGS_1984\",SPHEROID[\"WGS_1984\",\
    6378137.0,298.257223563]],PRIMEM[\"Greenwich\",0.0],UNIT[\"Degree\",0.0174532925199433]]";

const OGC_UTM31N: &str = r#"PROJCS["WGS 84 / UTM zone 31N",
    GEOGCS["WGS 84",
        DATUM["WGS_1984",
            SPHEROID["WGS 84",6378137,298.257223563,AUTHORITY["EPSG","7030"]],
            AUTHORITY["EPSG","6326"]],
        PRIMEM["Greenwich",0,AUTHORITY["EPSG","8901"]],
        UNIT["degree",0.0174532925199433,AUTHORITY["EPSG","9122"]],
        AUTHORITY["EPSG","4326"]],
    PROJECTION["Transverse_Mercator"],
    PARAMETER["latitude_of_origin",0],
    PARAMETER["central_meridian",3],
    PARAMETER["scale_factor",0.9996],
    PARAMETER["false_easting",500000],
    PARAMETER["false_northing",0],
    UNIT["metre",1,AUTHORITY["EPSG","9001"]],
    AXIS["Easting",EAST],
    AXIS["Northing",NORTH],
    AUTHORITY["EPSG","32631"]]"#;

const WKT2_GDA94: &str = r#"GEOGCRS["GDA94",
    DATUM["Geocentric Datum of Australia 1994",
        ELLIPSOID["GRS 1980",6378137,298.257222101,LENGTHUNIT["metre",1]]],
    PRIMEM["Greenwich",0,ANGLEUNIT["degree",0.0174532925199433]],
    CS[ellipsoidal,2],
        AXIS["geodetic latitude (Lat)",north,ORDER[1],ANGLEUNIT["degree",0.0174532925199433]],
        AXIS["geodetic longitude (Lon)",east,ORDER[2],ANGLEUNIT["degree",0.0174532925199433]],
    ID["EPSG",4283]]"#;

#[test]
fn sidecar_wkt_gives_the_crs() {
    assert_eq!(crs_of_wkt(ESRI_WGS84), Ok(geo(Some(4326))));
    assert_eq!(crs_of_wkt(OGC_UTM31N), Ok(proj(32631)));
    assert_eq!(crs_of_wkt(WKT2_GDA94), Ok(geo(Some(4283))));
    // WGS 84 UTM zones by name alone, both spellings and hemispheres
    let utm = |name: &str| {
        format!(
            "PROJCS[\"{name}\",{ESRI_WGS84},PROJECTION[\"Transverse_Mercator\"],\
             UNIT[\"Meter\",1.0]]"
        )
    };
    assert_eq!(crs_of_wkt(&utm("WGS_1984_UTM_Zone_56S")), Ok(proj(32756)));
    assert_eq!(crs_of_wkt(&utm("WGS 84 / UTM zone 1N")), Ok(proj(32601)));
    assert_eq!(
        crs_of_wkt(&utm("UTM Zone 60, Southern Hemisphere")),
        Ok(proj(32760))
    );
    // another datum's UTM zone, without a code: recorded by its name
    let nad83 = r#"PROJCS["NAD83 / UTM zone 10N",GEOGCS["NAD83",DATUM["North_American_Datum_1983",
        SPHEROID["GRS 1980",6378137,298.257222101]],UNIT["degree",0.0174532925199433]],
        PROJECTION["Transverse_Mercator"],UNIT["metre",1]]"#;
    assert_eq!(
        crs_of_wkt(nad83),
        Ok(Crs::Projected {
            epsg: None,
            citation: Some("NAD83 / UTM zone 10N".into())
        })
    );
    // a geographic CRS on an unnamed datum: user-defined geographic
    let other = "GEOGCS[\"Mars 2000\",DATUM[\"D_Mars_2000\",SPHEROID[\"Mars\",3396190,169.89]],\
                 UNIT[\"Degree\",0.0174532925199433]]";
    assert_eq!(crs_of_wkt(other), Ok(geo(None)));
    // a compound CRS: its horizontal part
    let compound = format!("COMPD_CS[\"UTM + height\",{OGC_UTM31N},VERT_CS[\"h\"]]");
    assert_eq!(crs_of_wkt(&compound), Ok(proj(32631)));
}

#[test]
fn sidecar_wkt_errors_say_what_is_wrong() {
    let feet = "PROJCS[\"NAD83 / California zone 6 (ftUS)\",GEOGCS[\"NAD83\"],\
                UNIT[\"US survey foot\",0.304800609601219]]";
    let grads = "GEOGCS[\"NTF (Paris)\",DATUM[\"NTF\"],UNIT[\"grad\",0.0157079632679489]]";
    for (text, says) in [
        (feet, "only metres are supported"),
        (grads, "only degrees are supported"),
        ("LOCAL_CS[\"tank\",UNIT[\"metre\",1]]", "LOCAL_CS"),
        ("not wkt at all", "expected [ after not"),
        ("", "expected WKT"),
        ("GEOGCS[\"WGS 84\"", "not closed"),
        ("GEOGCS[\"WGS 84]", "quoted string is not closed"),
        ("GEOGCS[\"WGS 84\"] trailing", "unexpected text"),
        ("GEOGCS[\"WGS 84\",,]", "empty value"),
    ] {
        let e = crs_of_wkt(text).unwrap_err();
        assert!(e.contains(says), "{text}: {e}");
    }
    let deep = format!("{}{}", "A[".repeat(100), "]".repeat(100));
    assert!(crs_of_wkt(&deep).unwrap_err().contains("64 levels"));
}

#[test]
fn written_sidecars_read_back() {
    assert_eq!(
        crs_of_wkt(&wkt_of(&geo(Some(4326))).unwrap()),
        Ok(geo(Some(4326)))
    );
    for code in (32601..=32660).chain(32701..=32760) {
        let wkt = wkt_of(&proj(code)).unwrap();
        assert_eq!(crs_of_wkt(&wkt), Ok(proj(code)), "{wkt}");
    }
    // zone 56: central meridian 153° E, southern false northing
    let w = wkt_of(&proj(32756)).unwrap();
    assert!(
        w.contains("\"Central_Meridian\",153") && w.contains("10000000.0"),
        "{w}"
    );
    assert_eq!(wkt_of(&geo(Some(4258))), None);
    assert_eq!(wkt_of(&proj(3857)), None);
    assert_eq!(wkt_of(&Crs::None), None);
}

#[test]
fn declarations_fill_in_or_must_agree() {
    let own = proj(32631);
    let ok = reconcile("g.tif", own.clone(), CrsSource::File, proj(32631)).unwrap();
    assert_eq!(ok, (own.clone(), CrsSource::File));
    let e = reconcile("g.tif", own.clone(), CrsSource::File, geo(Some(4326)))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("g.tif") && e.contains("EPSG:4326") && e.contains("EPSG:32631"),
        "{e}"
    );
    let e = reconcile("g.tif", own, CrsSource::File, proj(32632))
        .unwrap_err()
        .to_string();
    assert!(e.contains("EPSG:32632") && e.contains("EPSG:32631"), "{e}");
    // a user-defined CRS of the same kind takes the declared code, keeping its citation
    let user = Crs::Projected {
        epsg: None,
        citation: Some("local grid".into()),
    };
    let (crs, source) = reconcile("g.tif", user, CrsSource::File, proj(32631)).unwrap();
    assert_eq!(
        crs,
        Crs::Projected {
            epsg: Some(32631),
            citation: Some("local grid".into())
        }
    );
    assert_eq!(source, CrsSource::Declared);
    let (crs, _) = reconcile("g.tif", geo(None), CrsSource::File, geo(Some(4326))).unwrap();
    assert_eq!(crs, geo(Some(4326)));
    assert!(reconcile("g.tif", geo(None), CrsSource::File, proj(32631)).is_err());
}
