//! The `.pvd` collection: a VTKFile of type `Collection` whose `DataSet` entries name each
//! `.vtu` (relative to the `.pvd`) with its `timestep`, the form ParaView reads as a time series.
//! Written with quick-xml's event writer (escaping included), never by string formatting.

use std::io::Write;

use quick_xml::events::{BytesDecl, BytesEnd, BytesStart, Event};
use quick_xml::Writer;

/// The collection text for `(time, file name)` entries, in order.
pub fn collection(entries: &[(f64, String)]) -> Result<Vec<u8>, String> {
    let err = |e: quick_xml::Error| format!("writing the .pvd: {e}");
    let mut w = Writer::new_with_indent(Vec::new(), b' ', 2);
    w.write_event(Event::Decl(BytesDecl::new(b"1.0", None, None)))
        .map_err(err)?;
    let mut root = BytesStart::borrowed_name(b"VTKFile");
    root.push_attribute(("type", "Collection"));
    root.push_attribute(("version", "0.1"));
    root.push_attribute(("byte_order", "LittleEndian"));
    w.write_event(Event::Start(root)).map_err(err)?;
    w.write_event(Event::Start(BytesStart::borrowed_name(b"Collection")))
        .map_err(err)?;
    for (t, file) in entries {
        // Rust's shortest round-trip form: the time is read back bit for bit
        let time = format!("{t:?}");
        let mut d = BytesStart::borrowed_name(b"DataSet");
        d.push_attribute(("timestep", time.as_str()));
        d.push_attribute(("group", ""));
        d.push_attribute(("part", "0"));
        d.push_attribute(("file", file.as_str()));
        w.write_event(Event::Empty(d)).map_err(err)?;
    }
    w.write_event(Event::End(BytesEnd::borrowed(b"Collection")))
        .map_err(err)?;
    w.write_event(Event::End(BytesEnd::borrowed(b"VTKFile")))
        .map_err(err)?;
    let mut text = w.into_inner();
    text.write_all(b"\n")
        .map_err(|e| format!("writing the .pvd: {e}"))?;
    Ok(text)
}

/// The `(timestep, file)` entries of a collection's text (for tests and round trips).
pub fn entries(text: &str) -> Result<Vec<(f64, String)>, String> {
    use quick_xml::Reader;
    let mut reader = Reader::from_str(text);
    let mut buf = Vec::new();
    let mut out = Vec::new();
    loop {
        match reader.read_event(&mut buf) {
            Ok(Event::Empty(e)) | Ok(Event::Start(e)) if e.name() == b"DataSet" => {
                let (mut t, mut f) = (None, None);
                for a in e.attributes() {
                    let a = a.map_err(|e| format!(".pvd: {e}"))?;
                    let v = a
                        .unescape_and_decode_value(&reader)
                        .map_err(|e| format!(".pvd: {e}"))?;
                    match a.key {
                        b"timestep" => {
                            t = Some(v.parse::<f64>().map_err(|e| format!(".pvd: {v}: {e}"))?)
                        }
                        b"file" => f = Some(v),
                        _ => {}
                    }
                }
                match (t, f) {
                    (Some(t), Some(f)) => out.push((t, f)),
                    _ => return Err(".pvd: a DataSet without timestep or file".into()),
                }
            }
            Ok(Event::Eof) => break,
            Err(e) => return Err(format!(".pvd: {e}")),
            _ => {}
        }
        buf.clear();
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    //! The collection round-trips: its entries read back with the same times (bit for bit) and
    //! file names, an `&` in a name escaped.
    use super::*;

    #[test]
    fn collection_entries_round_trip() {
        let e = vec![
            (0.0, "a_0000.vtu".to_string()),
            (0.1 + 0.2, "b&c_0001.vtu".to_string()),
        ];
        let text = String::from_utf8(collection(&e).unwrap()).unwrap();
        assert!(text.contains("b&amp;c_0001.vtu"), "{text}");
        assert_eq!(entries(&text).unwrap(), e);
    }
}
