//! The codec against the files a real CoppeliaSim 4.5.1 wrote (`tests/coppeliasim-xml/`).

use super::*;
use crate::coppelia::{SPECIAL_DETECTABLE, SPECIAL_RENDERABLE};
use proptest::prelude::*;

const COURSE: &str = include_str!("../../../../../tests/coppeliasim-xml/course-4.5.1.simscene.xml");
const LINE: &str =
    include_str!("../../../../../tests/coppeliasim-xml/line-plane-4.5.1.simmodel.xml");
const TWO_RECTS: &str =
    include_str!("../../../../../tests/coppeliasim-xml/mesh-two-rects-4.5.1.simmodel.xml");

/// Elements the writer leaves out on purpose (see the module documentation).
const OMITTED: [&str; 3] = [
    "dnaString_base64Coded",
    "uniquePersistentString_base64Coded",
    "sceneUniquePersistentIdString_base64Coded",
];

/// The element paths of `text` in document order (`CoppeliaSim/sceneObject/shape/...`),
/// without the omitted elements.
pub(crate) fn structure(text: &str) -> Vec<String> {
    use quick_xml::events::Event;
    let mut reader = quick_xml::Reader::from_str(text);
    let mut stack: Vec<String> = Vec::new();
    let mut out = Vec::new();
    loop {
        match reader.read_event().unwrap() {
            Event::Start(e) => {
                stack.push(String::from_utf8_lossy(e.name().as_ref()).into_owned());
                out.push(stack.join("/"));
            }
            Event::Empty(e) => {
                let name = String::from_utf8_lossy(e.name().as_ref()).into_owned();
                out.push(format!("{}/{name}", stack.join("/")));
            }
            Event::End(_) => {
                stack.pop();
            }
            Event::Eof => break,
            _ => {}
        }
    }
    out.retain(|p| !OMITTED.iter().any(|o| p.ends_with(o)));
    out
}

fn close(a: [f32; 3], b: [f32; 3]) -> bool {
    a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-6)
}

fn shape(o: &XmlObject) -> &Shape {
    match &o.body {
        Body::Shape(s) => s,
        Body::Dummy(_) => panic!("{} is a dummy", o.alias),
    }
}

#[test]
fn the_reference_mesh_model_reads_as_two_green_rectangles_in_the_shape_frame() {
    let doc = read(TWO_RECTS).unwrap();
    assert_eq!(doc.kind, FileKind::Model);
    assert_eq!(doc.objects.len(), 1);
    let o = &doc.objects[0];
    assert_eq!(
        (o.alias.as_str(), o.handle, o.parent),
        ("MazeMesh", 6, None)
    );
    assert!(o.model_base);
    assert_eq!(o.quaternion, [1.0, 0.0, 0.0, 0.0]);
    let s = shape(o);
    assert_eq!(s.colour, [0.0, 1.0, 0.0]);
    assert!(s.is_static && !s.respondable);
    assert_eq!(s.mesh.triangles(), 4);
    // Vertices are stored relative to the box frame (0.35, 0.5, 0.001).
    assert!(close(s.mesh.vertices[0], [0.85, 0.05, 0.001]));
    let (lo, hi) = s.mesh.bounds().unwrap();
    let near = |a: [f64; 3], b: [f64; 3]| a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-6);
    assert!(near(lo, [-0.35, -0.05, 0.001]) && near(hi, [1.05, 1.05, 0.001]));
    assert_eq!(
        o.special & (SPECIAL_DETECTABLE | SPECIAL_RENDERABLE),
        SPECIAL_DETECTABLE | SPECIAL_RENDERABLE
    );
}

#[test]
fn the_reference_course_scene_reads_as_its_five_objects() {
    let doc = read(COURSE).unwrap();
    assert_eq!(doc.kind, FileKind::Scene);
    let aliases: Vec<&str> = doc.objects.iter().map(|o| o.alias.as_str()).collect();
    assert_eq!(aliases, ["Floor", "Maze", "Line", "Start", "End"]);
    assert!(matches!(doc.objects[1].body, Body::Dummy(Dummy { size, .. }) if size == 0.05));
    assert_eq!(doc.objects[1].special, 0);
    let line = &doc.objects[2];
    assert_eq!(line.position, [0.0, 0.0, 0.001]);
    assert_eq!(shape(line).primitive, Primitive::Plane([0.6, 0.1, 0.0001]));
    assert_eq!(shape(&doc.objects[4]).colour, [1.0, 0.0, 0.0]);
    let line_model = read(LINE).unwrap();
    assert_eq!(line_model.objects[0].alias, "LineModel");
    assert_eq!(shape(&line_model.objects[0]).mesh.vertices.len(), 4);
}

#[test]
fn what_we_write_has_the_element_structure_of_what_coppeliasim_wrote() {
    for (name, reference) in [
        ("course scene", COURSE),
        ("Line model", LINE),
        ("mesh model", TWO_RECTS),
    ] {
        let ours = write(&read(reference).unwrap());
        assert_eq!(structure(&ours), structure(reference), "{name}");
    }
}

#[test]
fn writing_then_reading_gives_the_document_back_and_the_same_bytes_each_time() {
    let doc = read(TWO_RECTS).unwrap();
    let text = write(&doc);
    assert_eq!(text, write(&doc), "deterministic");
    let back = read(&text).unwrap();
    assert_eq!(back.objects.len(), 1);
    let (a, b) = (shape(&doc.objects[0]), shape(&back.objects[0]));
    assert_eq!(a.mesh.indices, b.mesh.indices);
    assert!(
        a.mesh
            .vertices
            .iter()
            .zip(&b.mesh.vertices)
            .all(|(x, y)| close(*x, *y))
    );
    assert_eq!((a.colour, a.primitive), (b.colour, b.primitive));
    let scene = read(COURSE).unwrap();
    assert_eq!(read(&write(&scene)).unwrap().objects.len(), 5);
    // The box and thumbnail of the reference mesh model come out as CoppeliaSim wrote them.
    assert!(
        text.contains(
            "<modelBoundingBoxSize>1.4000e+00 1.1000e+00 0.0000e+00</modelBoundingBoxSize>"
        )
    );
    assert!(text.contains("<position>3.5000e-01 5.0000e-01 1.0000e-03</position>"));
    assert!(text.contains("<edges>255 15</edges>"));
}

#[test]
fn numbers_are_written_like_c_printf_percent_4e() {
    assert_eq!(write::sci_for_tests(1.0), "1.0000e+00");
    assert_eq!(write::sci_for_tests(-0.05), "-5.0000e-02");
    assert_eq!(write::sci_for_tests(0.0), "0.0000e+00");
    assert_eq!(write::sci_for_tests(12345.0), "1.2345e+04");
}

#[test]
fn what_is_not_read_is_a_clear_error() {
    let cases = [
        ("not xml <", "not well-formed"),
        ("<Other/>", "root element"),
        (
            "<CoppeliaSim><filetype>simpleModel</filetype></CoppeliaSim>",
            "simpleModel",
        ),
        ("<CoppeliaSim></CoppeliaSim>", "filetype"),
    ];
    for (text, needle) in cases {
        let e = read(text).unwrap_err().to_string();
        assert!(e.contains(needle), "{text}: {e}");
    }
    let joint = TWO_RECTS
        .replace("<shape>", "<joint>")
        .replace("</shape>", "</joint>");
    assert!(read(&joint).unwrap_err().to_string().contains("<joint>"));
    let compound = TWO_RECTS
        .replace("<mesh>", "<compound>")
        .replace("</mesh>", "</compound>");
    assert!(
        read(&compound)
            .unwrap_err()
            .to_string()
            .contains("compound")
    );
    let out_of_range = TWO_RECTS.replace("<indices>0 1 2", "<indices>0 1 9");
    assert!(
        read(&out_of_range)
            .unwrap_err()
            .to_string()
            .contains("index 9")
    );
    let orphan = TWO_RECTS.replace("<parentHandle>-1<", "<parentHandle>3<");
    assert!(
        read(&orphan)
            .unwrap_err()
            .to_string()
            .contains("parent handle 3")
    );
    let own_parent = TWO_RECTS.replace("<parentHandle>-1<", "<parentHandle>6<");
    assert!(
        read(&own_parent)
            .unwrap_err()
            .to_string()
            .contains("own ancestor")
    );
    let bad_number = TWO_RECTS.replace("<bbSize>1.4000e+00", "<bbSize>x");
    assert!(read(&bad_number).is_ok(), "bbSize is not read");
    let bad_vertex = TWO_RECTS.replace("<vertices>5.0000e-01", "<vertices>abc");
    assert!(read(&bad_vertex).unwrap_err().to_string().contains("'abc'"));
    let deep = "<a>".repeat(100_000);
    assert!(read(&deep).unwrap_err().to_string().contains("deeper"));
}

proptest! {
    #[test]
    fn the_reader_never_panics_on_cut_or_damaged_files(cut in 0usize..18_000, at in 0usize..18_000, byte in any::<u8>()) {
        let mut bytes = TWO_RECTS.as_bytes()[..cut.min(TWO_RECTS.len())].to_vec();
        if at < bytes.len() {
            bytes[at] = byte;
        }
        let _ = read(&String::from_utf8_lossy(&bytes));
    }
}
