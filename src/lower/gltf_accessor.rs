//! glTF accessors read by our own code, every range checked before a byte
//! is read: a file's numbers (offsets, strides, counts) are not trusted,
//! and the `gltf` crate's readers index slices with them unchecked. An
//! accessor's elements are converted as the glTF 2.0 specification says
//! (normalised integers, §3.11: `max(c / (2^(b-1) - 1), -1)` for signed,
//! `c / (2^b - 1)` for unsigned ones).

use gltf::accessor::{Accessor, DataType, Dimensions};

/// The buffers' bytes by buffer index.
pub type Buffers<'a> = [std::borrow::Cow<'a, [u8]>];

/// How many numbers an element of `dimensions` holds.
fn components(dimensions: Dimensions) -> usize {
    match dimensions {
        Dimensions::Scalar => 1,
        Dimensions::Vec2 => 2,
        Dimensions::Vec3 => 3,
        Dimensions::Vec4 => 4,
        Dimensions::Mat2 => 4,
        Dimensions::Mat3 => 9,
        Dimensions::Mat4 => 16,
    }
}

/// The bytes one number of `data_type` takes.
fn width(data_type: DataType) -> usize {
    match data_type {
        DataType::I8 | DataType::U8 => 1,
        DataType::I16 | DataType::U16 => 2,
        DataType::U32 | DataType::F32 => 4,
    }
}

/// The number at the start of `b` as f32, normalised when `normalized`.
fn number(b: &[u8], data_type: DataType, normalized: bool) -> f32 {
    let (value, scale) = match data_type {
        DataType::I8 => (b[0] as i8 as f32, 127.0),
        DataType::U8 => (b[0] as f32, 255.0),
        DataType::I16 => (i16::from_le_bytes([b[0], b[1]]) as f32, 32_767.0),
        DataType::U16 => (u16::from_le_bytes([b[0], b[1]]) as f32, 65_535.0),
        DataType::U32 => (u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f32, 1.0),
        DataType::F32 => (f32::from_le_bytes([b[0], b[1], b[2], b[3]]), 1.0),
    };
    match normalized && data_type != DataType::F32 {
        true => (value / scale).max(-1.0),
        false => value,
    }
}

/// The bytes of `accessor`'s elements and the stride between them, every
/// range checked against the view and the buffer.
fn elements<'b>(
    accessor: &Accessor,
    buffers: &'b Buffers,
    element: usize,
) -> Result<(&'b [u8], usize), String> {
    let index = accessor.index();
    if accessor.sparse().is_some() {
        return Err(format!(
            "accessor {index} is sparse, which ptsc does not read"
        ));
    }
    let view = (accessor.view()).ok_or(format!("accessor {index} has no buffer view"))?;
    let buffer = (buffers.get(view.buffer().index())).ok_or("a buffer was not read")?;
    let in_buffer = (view.offset().checked_add(view.length()))
        .and_then(|end| buffer.get(view.offset()..end))
        .ok_or(format!(
            "buffer view {} reaches past its buffer's {} bytes",
            view.index(),
            buffer.len()
        ))?;
    let stride = view.stride().unwrap_or(element);
    if stride < element {
        return Err(format!(
            "buffer view {} has a stride of {stride} bytes, less than accessor {index}'s {element}-byte elements",
            view.index()
        ));
    }
    let count = accessor.count();
    if count == 0 {
        return Err(format!("accessor {index} has no elements"));
    }
    let end = (stride.checked_mul(count - 1))
        .and_then(|s| s.checked_add(element))
        .and_then(|s| s.checked_add(accessor.offset()));
    let bytes = end
        .and_then(|end| in_buffer.get(accessor.offset()..end))
        .ok_or(format!(
            "accessor {index} claims {count} elements, more than its buffer view holds"
        ))?;
    Ok((bytes, stride))
}

/// `accessor`'s elements as `N` floats each, when its elements have `N`
/// numbers (`what` names it in errors: "positions", …).
pub fn floats<const N: usize>(
    accessor: &Accessor,
    buffers: &Buffers,
    what: &str,
) -> Result<Vec<[f32; N]>, String> {
    let n = components(accessor.dimensions());
    if n != N {
        return Err(format!(
            "the {what} (accessor {}) have {n} numbers each, not {N}",
            accessor.index()
        ));
    }
    let (data_type, normalized) = (accessor.data_type(), accessor.normalized());
    let w = width(data_type);
    let (bytes, stride) = elements(accessor, buffers, w * N)?;
    let out = (0..accessor.count())
        .map(|k| {
            let e = &bytes[k * stride..];
            std::array::from_fn(|c| number(&e[c * w..], data_type, normalized))
        })
        .collect();
    Ok(out)
}

/// `accessor`'s elements as vertex indices (unsigned integers).
pub fn indices(accessor: &Accessor, buffers: &Buffers) -> Result<Vec<u32>, String> {
    let data_type = accessor.data_type();
    if components(accessor.dimensions()) != 1
        || !matches!(data_type, DataType::U8 | DataType::U16 | DataType::U32)
    {
        return Err(format!(
            "the indices (accessor {}) are not unsigned integers",
            accessor.index()
        ));
    }
    let w = width(data_type);
    let (bytes, stride) = elements(accessor, buffers, w)?;
    let out = (0..accessor.count())
        .map(|k| {
            let b = &bytes[k * stride..];
            match data_type {
                DataType::U8 => b[0] as u32,
                DataType::U16 => u16::from_le_bytes([b[0], b[1]]) as u32,
                _ => u32::from_le_bytes([b[0], b[1], b[2], b[3]]),
            }
        })
        .collect();
    Ok(out)
}
