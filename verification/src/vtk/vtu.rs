//! One [`Frame`] as a VTK XML UnstructuredGrid file (`.vtu`): vtkio's data model, written by
//! vtkio (XML version 1.0, little-endian, base64 binary data arrays with UInt64 headers;
//! coordinates and values as Float64, labels as Int32, connectivity and offsets as UInt64).

use std::path::Path;

use vtkio::model::{
    Attribute, Attributes, ByteOrder, CellType, DataArray, DataSet, ElementType, IOBuffer,
    UnstructuredGridPiece, Version, VertexNumbers, Vtk,
};

use crate::vtk::frame::{Array, Cells, Frame, Values};

fn attribute(a: &Array) -> Attribute {
    let elem = match a.components {
        1 => ElementType::Scalars {
            num_comp: 1,
            lookup_table: None,
        },
        3 => ElementType::Vectors,
        9 => ElementType::Tensors,
        n => ElementType::Generic(n as u32),
    };
    let data = match &a.values {
        Values::F64(v) => IOBuffer::F64(v.clone()),
        Values::I32(v) => IOBuffer::I32(v.clone()),
    };
    Attribute::DataArray(DataArray {
        name: a.name.clone(),
        elem,
        data,
    })
}

/// The frame in vtkio's model (the frame is assumed checked: [`Frame::check`]).
pub fn model(frame: &Frame, title: &str) -> Vtk {
    let (connectivity, offsets, types): (Vec<u64>, Vec<u64>, Vec<CellType>) = match &frame.cells {
        Cells::Triangles(t) => (
            t.iter().flatten().map(|&i| i as u64).collect(),
            (1..=t.len() as u64).map(|k| 3 * k).collect(),
            vec![CellType::Triangle; t.len()],
        ),
        Cells::Lines(l) => (
            l.iter().flatten().map(|&i| i as u64).collect(),
            (1..=l.len() as u64).map(|k| 2 * k).collect(),
            vec![CellType::Line; l.len()],
        ),
    };
    let piece = UnstructuredGridPiece {
        points: IOBuffer::F64(frame.points.iter().flatten().copied().collect()),
        cells: vtkio::model::Cells {
            cell_verts: VertexNumbers::XML {
                connectivity,
                offsets,
            },
            types,
        },
        data: Attributes {
            point: frame.point_data.iter().map(attribute).collect(),
            cell: frame.cell_data.iter().map(attribute).collect(),
        },
    };
    Vtk {
        version: Version::new((1, 0)),
        title: title.to_string(),
        byte_order: ByteOrder::LittleEndian,
        data: DataSet::inline(piece),
        file_path: None,
    }
}

/// Checks the frame and writes it to `path` (a `.vtu`).
pub fn write(frame: &Frame, title: &str, path: &Path) -> Result<(), String> {
    frame.check()?;
    model(frame, title)
        .export(path)
        .map_err(|e| format!("{}: {e}", path.display()))
}
