//! NumPy `.npy` points in, indices out (issue 12, item 3), checked against the NPY format as
//! NumPy documents it (`numpy.lib.format`): a 6-byte magic string `\x93NUMPY`, a major and a
//! minor version byte, the header length (2 bytes little-endian in version 1.0, 4 in 2.0 and
//! 3.0), the header (a Python dictionary literal with `descr`, `fortran_order` and `shape`,
//! padded with spaces and ended by a newline so that the data start on a multiple of 64), then
//! the data.

use condt::{reconstruct, triangulate, Params, Point};
use condt_io::{
    parse_npy, read_points, write_npy_edges, write_npy_points, write_npy_triangles,
    write_npy_triangulation_edges,
};

/// A `.npy` file built here byte by byte from the specification, independently of the writer.
fn npy_file(major: u8, dict: &str, data: &[u8]) -> Vec<u8> {
    let length_bytes = if major == 1 { 2 } else { 4 };
    let unpadded = 8 + length_bytes + dict.len() + 1;
    let header = format!("{dict}{}\n", " ".repeat((64 - unpadded % 64) % 64));
    let mut out = b"\x93NUMPY".to_vec();
    out.extend_from_slice(&[major, 0]);
    if major == 1 {
        out.extend_from_slice(&(header.len() as u16).to_le_bytes());
    } else {
        out.extend_from_slice(&(header.len() as u32).to_le_bytes());
    }
    out.extend_from_slice(header.as_bytes());
    assert_eq!(out.len() % 64, 0);
    out.extend_from_slice(data);
    out
}

fn sample_points() -> Vec<Point> {
    vec![
        Point::new(0.0, 0.0),
        Point::new(1.5, -2.25),
        Point::new(1e-300, 1e300),
        Point::new(-0.1, 0.3),
        Point::new(3.0, 3.0),
    ]
}

#[test]
fn the_points_writer_emits_the_version_1_0_layout_byte_by_byte() {
    let points = sample_points();
    let mut written = Vec::new();
    write_npy_points(&mut written, &points).unwrap();
    let data: Vec<u8> = points
        .iter()
        .flat_map(|p| [p.x.to_le_bytes(), p.y.to_le_bytes()])
        .flatten()
        .collect();
    let expected = npy_file(
        1,
        "{'descr': '<f8', 'fortran_order': False, 'shape': (5, 2), }",
        &data,
    );
    assert_eq!(written, expected);
    // The header length field: 118 = 128 - 10, little-endian.
    assert_eq!(&written[6..10], &[1, 0, 118, 0]);
    assert_eq!(parse_npy(&written, "p.npy").unwrap(), points);
}

#[test]
fn float64_and_float32_in_both_byte_orders_versions_and_memory_orders_are_read() {
    let points = sample_points();
    let narrow: Vec<Point> = points
        .iter()
        .map(|p| Point::new(f64::from(p.x as f32), f64::from(p.y as f32)))
        .filter(|p| p.x.is_finite() && p.y.is_finite())
        .collect();
    let rows = |pts: &[Point], f: &dyn Fn(f64) -> Vec<u8>| -> Vec<u8> {
        pts.iter()
            .flat_map(|p| [f(p.x), f(p.y)])
            .flatten()
            .collect()
    };
    let columns = |pts: &[Point], f: &dyn Fn(f64) -> Vec<u8>| -> Vec<u8> {
        let xs = pts.iter().flat_map(|p| f(p.x));
        xs.chain(pts.iter().flat_map(|p| f(p.y))).collect()
    };
    let le64 = |v: f64| v.to_le_bytes().to_vec();
    let be64 = |v: f64| v.to_be_bytes().to_vec();
    let le32 = |v: f64| (v as f32).to_le_bytes().to_vec();
    let be32 = |v: f64| (v as f32).to_be_bytes().to_vec();
    let n = points.len();
    let m = narrow.len();
    let cases: Vec<(Vec<u8>, &Vec<Point>)> = vec![
        (
            npy_file(
                1,
                &format!("{{'descr': '<f8', 'fortran_order': False, 'shape': ({n}, 2), }}"),
                &rows(&points, &le64),
            ),
            &points,
        ),
        (
            npy_file(
                1,
                &format!("{{'descr': '>f8', 'fortran_order': False, 'shape': ({n}, 2), }}"),
                &rows(&points, &be64),
            ),
            &points,
        ),
        (
            npy_file(
                2,
                &format!("{{'descr': '<f8', 'fortran_order': False, 'shape': ({n}, 2), }}"),
                &rows(&points, &le64),
            ),
            &points,
        ),
        (
            npy_file(
                3,
                &format!("{{'descr': '<f8', 'fortran_order': True, 'shape': ({n}, 2), }}"),
                &columns(&points, &le64),
            ),
            &points,
        ),
        (
            npy_file(
                1,
                &format!("{{'descr': '<f4', 'fortran_order': False, 'shape': ({m}, 2), }}"),
                &rows(&narrow, &le32),
            ),
            &narrow,
        ),
        (
            npy_file(
                1,
                &format!("{{'descr': '>f4', 'fortran_order': True, 'shape': ({m}, 2), }}"),
                &columns(&narrow, &be32),
            ),
            &narrow,
        ),
    ];
    for (k, (bytes, expected)) in cases.iter().enumerate() {
        assert_eq!(&parse_npy(bytes, "p.npy").unwrap(), *expected, "case {k}");
    }
    // An empty array is read as no points.
    let empty = npy_file(
        1,
        "{'descr': '<f8', 'fortran_order': False, 'shape': (0, 2), }",
        &[],
    );
    assert!(parse_npy(&empty, "e.npy").unwrap().is_empty());
}

#[test]
fn bad_files_are_refused_with_a_message() {
    let dict = |descr: &str, shape: &str| {
        format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': {shape}, }}")
    };
    let two = [1.0f64, 2.0, 3.0, 4.0]
        .iter()
        .flat_map(|v| v.to_le_bytes())
        .collect::<Vec<u8>>();
    let good = npy_file(1, &dict("<f8", "(2, 2)"), &two);
    let mut with_nan = two.clone();
    with_nan[16..24].copy_from_slice(&f64::NAN.to_le_bytes());
    let mut version_4 = good.clone();
    version_4[6] = 4;
    let cases: Vec<(Vec<u8>, &str)> = vec![
        (b"0 0\n1 1\n".to_vec(), "not a NumPy .npy file"),
        // Cut inside the magic or the version: a damaged array (a reviewer's report: 6 and 7
        // bytes were said not to start with the magic they start with).
        (good[..1].to_vec(), "the file ends inside its header"),
        (good[..6].to_vec(), "the file ends inside its header"),
        (good[..7].to_vec(), "the file ends inside its header"),
        (good[..9].to_vec(), "the file ends inside its header"),
        (Vec::new(), "not a NumPy .npy file"),
        (b"\x93NUMPZ\x01\x00".to_vec(), "not a NumPy .npy file"),
        (b"\x93N".to_vec(), "the file ends inside its header"),
        (good[..40].to_vec(), "ends inside its header"),
        (
            good[..good.len() - 1].to_vec(),
            "the header announces 2 points (32 bytes of data), the file ends after 31 bytes",
        ),
        ([good.clone(), vec![0]].concat(), "bytes after the 2 points"),
        (version_4, "version 4.0 is not supported"),
        (
            npy_file(1, &dict("<c8", "(2, 2)"), &[0; 32]),
            "element type \"<c8\" is not supported",
        ),
        (
            npy_file(1, &dict("<f8", "(4,)"), &two),
            "shape (4,) is not (n, 2)",
        ),
        (
            npy_file(1, &dict("<f8", "(1, 2, 2)"), &two),
            "shape (1, 2, 2) is not (n, 2)",
        ),
        (
            npy_file(1, &dict("<f8", "(2, 2)"), &with_nan),
            "row 1: the point (NaN, 4) is not finite",
        ),
        (
            npy_file(1, "{'descr': '<f8', 'shape': (2, 2), }", &two),
            "no 'fortran_order'",
        ),
        (
            npy_file(1, &dict("<f8", "(99999999999999999999, 2)"), &two),
            "not a size",
        ),
        (
            npy_file(1, &dict("<f8", "(400000000, 2)"), &two),
            "the most condt accepts",
        ),
    ];
    for (bytes, says) in cases {
        let err = parse_npy(&bytes, "bad.npy").unwrap_err();
        let text = err.to_string();
        assert!(text.starts_with("bad.npy: "), "{text}");
        assert!(text.contains(says), "{says:?} not in {text:?}");
        assert_eq!(err.line, None);
    }
}

/// The layouts image tools hand over are refused with the way to save them as (n, 2), as
/// Python's `condt.reconstruct` names them: an image user's review saved OpenCV's contours,
/// `numpy.save("c.npy", contour)` of shape (n, 1, 2), and the message gave only the shape. The
/// data are read by no one: the shape alone decides.
#[test]
fn shapes_other_tools_hand_over_are_refused_with_the_fix() {
    let data = [0u8; 8 * 24];
    for (shape, says) in [
        (
            "(12, 1, 2)",
            "OpenCV's contour layout? save points.reshape(-1, 2)",
        ),
        (
            "(2, 6, 1, 2)",
            "OpenCV's contours stacked? save numpy.vstack(contours).reshape(-1, 2)",
        ),
        ("(2, 12)", "points by column? save points.T"),
        ("(2, 6, 2)", "contours stacked? save numpy.vstack(contours)"),
        (
            "(8, 6, 4)",
            "a colour image? make an edge image or a mask of it first (skimage.color.rgb2gray, \
             then a threshold or skimage.feature.canny), then save points: \
             numpy.argwhere(edges)[:, ::-1] gives its pixels as (x, y)",
        ),
        (
            "(8, 3)",
            "save the two coordinate columns, such as points[:, :2]",
        ),
        (
            "(6, 4)",
            "save the two coordinate columns, such as points[:, :2]",
        ),
        (
            "(6, 8)",
            "an image or a mask? save points: numpy.argwhere(edges)[:, ::-1] gives an edge \
             image's pixels as (x, y), and mask & ~scipy.ndimage.binary_erosion(mask) a filled \
             mask's boundary; a label image (regions numbered)? b = \
             skimage.segmentation.find_boundaries(labels, mode='subpixel'), then \
             numpy.argwhere(b)[:, ::-1] / 2 gives the borders between regions, junctions included; \
             a table? save the two coordinate columns, such as points[:, :2]",
        ),
    ] {
        let dict = format!("{{'descr': '<i4', 'fortran_order': False, 'shape': {shape}, }}");
        let file = npy_file(1, &dict, &data[..4 * 24]);
        let text = parse_npy(&file, "c.npy").unwrap_err().to_string();
        assert!(
            text.starts_with(&format!("c.npy: shape {shape} is not (n, 2)")),
            "{text}"
        );
        assert!(text.ends_with(says), "{says:?} not at the end of {text:?}");
    }
    // A boolean mask saved whole: its type is refused, and the fix its shape calls for named.
    let dict = "{'descr': '|b1', 'fortran_order': False, 'shape': (8, 12), }";
    let text = parse_npy(&npy_file(1, dict, &data[..96]), "mask.npy")
        .unwrap_err()
        .to_string();
    assert!(
        text.contains("element type \"|b1\" is not supported"),
        "{text}"
    );
    assert!(
        text.contains("save points: numpy.argwhere(edges)[:, ::-1]"),
        "{text}"
    );
    // Other shapes keep the bare message.
    for (shape, bytes) in [("(2, 3, 3)", 144), ("(3, 7)", 168)] {
        let dict = format!("{{'descr': '<f8', 'fortran_order': False, 'shape': {shape}, }}");
        let text = parse_npy(&npy_file(1, &dict, &data[..bytes]), "c.npy")
            .unwrap_err()
            .to_string();
        assert!(text.ends_with("one row `x y` per point"), "{text}");
    }
}

/// The index writers: version 1.0 headers byte by byte, uint32 data, the same rows as the text
/// writers.
#[test]
fn edges_and_triangles_go_out_as_uint32_arrays_with_exact_headers() {
    let points: Vec<Point> = (0..40)
        .map(|i| {
            let t = f64::from(i) * 0.157;
            Point::new(t.cos() * (1.0 + 0.1 * f64::from(i % 3)), t.sin())
        })
        .collect();
    let tri = triangulate(&points).unwrap();
    let u32s = |bytes: &[u8]| -> Vec<usize> {
        bytes
            .chunks_exact(4)
            .map(|b| u32::from_le_bytes(b.try_into().unwrap()) as usize)
            .collect()
    };
    let triangles: Vec<[usize; 3]> = tri.triangles().collect();
    let mut out = Vec::new();
    write_npy_triangles(&mut out, &tri).unwrap();
    let data: Vec<usize> = triangles.iter().flatten().copied().collect();
    let dict = format!(
        "{{'descr': '<u4', 'fortran_order': False, 'shape': ({}, 3), }}",
        triangles.len()
    );
    assert_eq!(out[..128], npy_file(1, &dict, &[])[..]);
    assert_eq!(u32s(&out[128..]), data);

    let mut edges: Vec<[usize; 2]> = tri.edges().collect();
    edges.sort_unstable();
    let mut out = Vec::new();
    write_npy_triangulation_edges(&mut out, &tri).unwrap();
    let dict = format!(
        "{{'descr': '<u4', 'fortran_order': False, 'shape': ({}, 2), }}",
        edges.len()
    );
    assert_eq!(out[..128], npy_file(1, &dict, &[])[..]);
    assert_eq!(u32s(&out[128..]), edges.concat());

    let result = reconstruct(&points, &Params::default()).unwrap();
    let mut out = Vec::new();
    write_npy_edges(&mut out, &result).unwrap();
    let final_edges: Vec<usize> = result.edges().flatten().collect();
    let dict = format!(
        "{{'descr': '<u4', 'fortran_order': False, 'shape': ({}, 2), }}",
        final_edges.len() / 2
    );
    assert_eq!(out[..128], npy_file(1, &dict, &[])[..]);
    assert_eq!(u32s(&out[128..]), final_edges);
}

#[test]
fn read_points_reads_npy_by_its_name_in_any_case() {
    let dir = tempfile::tempdir().unwrap();
    let points = sample_points();
    let mut bytes = Vec::new();
    write_npy_points(&mut bytes, &points).unwrap();
    for name in ["p.npy", "P.NPY"] {
        let path = dir.path().join(name);
        std::fs::write(&path, &bytes).unwrap();
        assert_eq!(read_points(&path).unwrap(), points);
    }
    let path = dir.path().join("short.npy");
    std::fs::write(&path, &bytes[..100]).unwrap();
    let err = read_points(&path).unwrap_err();
    assert!(
        err.to_string()
            .ends_with("short.npy: the file ends inside its header"),
        "{err}"
    );
}

/// With NumPy installed, NumPy itself reads what condt writes and writes what condt reads;
/// without it the test says so and checks nothing more.
#[test]
fn numpy_agrees_when_it_is_installed() {
    let has_numpy = std::process::Command::new("python3")
        .args(["-c", "import numpy"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !has_numpy {
        println!("note: python3 with numpy is not installed; the NumPy cross-check is skipped");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let ours = dir.path().join("ours.npy");
    let theirs = dir.path().join("theirs.npy");
    let mut bytes = Vec::new();
    write_npy_points(&mut bytes, &sample_points()).unwrap();
    std::fs::write(&ours, &bytes).unwrap();
    let script = format!(
        "import numpy as np\n\
         a = np.load({ours:?})\n\
         assert a.dtype == np.float64 and a.shape == (5, 2), (a.dtype, a.shape)\n\
         assert a[2, 1] == 1e300 and a[1, 1] == -2.25\n\
         np.save({theirs:?}, np.asfortranarray(a[[0, 1, 3, 4]].astype('>f4')))\n",
        ours = ours.to_str().unwrap(),
        theirs = theirs.to_str().unwrap()
    );
    let run = std::process::Command::new("python3")
        .args(["-c", &script])
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let read = read_points(&theirs).unwrap();
    assert_eq!(read[1], Point::new(1.5, -2.25));
    assert_eq!(read.len(), 4);
    assert_eq!(read[2], Point::new(f64::from(-0.1f32), f64::from(0.3f32)));
}
