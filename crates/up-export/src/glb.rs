//! The binary side of a `.glb`: one buffer that every accessor reads, grown
//! a view at a time (each view 4-byte aligned, little-endian as glTF
//! requires), and the container that joins the JSON and that buffer.

use gltf_json as json;
use json::accessor::{ComponentType, GenericComponentType, Type};
use json::buffer::Target;
use json::validation::{Checked, USize64};
use json::{Accessor, Index, Root};

/// What an accessor's elements are made of.
pub enum Elements<'a> {
    F32(&'a [f32]),
    U16(&'a [u16]),
    U32(&'a [u32]),
}

impl Elements<'_> {
    fn component(&self) -> ComponentType {
        match self {
            Elements::F32(_) => ComponentType::F32,
            Elements::U16(_) => ComponentType::U16,
            Elements::U32(_) => ComponentType::U32,
        }
    }

    fn len(&self) -> usize {
        match self {
            Elements::F32(v) => v.len(),
            Elements::U16(v) => v.len(),
            Elements::U32(v) => v.len(),
        }
    }

    fn append(&self, out: &mut Vec<u8>) {
        match self {
            Elements::F32(v) => v.iter().for_each(|x| out.extend(x.to_le_bytes())),
            Elements::U16(v) => v.iter().for_each(|x| out.extend(x.to_le_bytes())),
            Elements::U32(v) => v.iter().for_each(|x| out.extend(x.to_le_bytes())),
        }
    }
}

/// Components per element of `type_`.
fn width(type_: Type) -> usize {
    match type_ {
        Type::Scalar => 1,
        Type::Vec2 => 2,
        Type::Vec3 => 3,
        Type::Vec4 | Type::Mat2 => 4,
        Type::Mat3 => 9,
        Type::Mat4 => 16,
    }
}

/// The binary chunk being written, and the document's views into it.
#[derive(Default)]
pub struct BinBuffer {
    pub bytes: Vec<u8>,
}

impl BinBuffer {
    /// Appends `data` as a view of its own and an accessor of `type_` over
    /// it; `target` marks vertex data and indices; `bounds` writes the min
    /// and max glTF asks of positions and animation times.
    pub fn accessor(
        &mut self,
        root: &mut Root,
        data: Elements,
        type_: Type,
        target: Option<Target>,
        bounds: bool,
    ) -> Index<Accessor> {
        let count = data.len() / width(type_);
        let offset = self.bytes.len();
        data.append(&mut self.bytes);
        let length = self.bytes.len() - offset;
        self.bytes.resize(length + offset + (4 - length % 4) % 4, 0);
        let view = root.push(json::buffer::View {
            buffer: Index::new(0),
            byte_length: USize64::from(length),
            byte_offset: Some(USize64::from(offset)),
            byte_stride: None,
            name: None,
            target: target.map(Checked::Valid),
            extensions: None,
            extras: Default::default(),
        });
        let (min, max) = match (&data, bounds) {
            (Elements::F32(v), true) => {
                let n = width(type_);
                let mut lo = vec![f32::INFINITY; n];
                let mut hi = vec![f32::NEG_INFINITY; n];
                for element in v.chunks_exact(n) {
                    for (k, &x) in element.iter().enumerate() {
                        lo[k] = lo[k].min(x);
                        hi[k] = hi[k].max(x);
                    }
                }
                (
                    Some(json::serialize::to_value(lo)),
                    Some(json::serialize::to_value(hi)),
                )
            }
            _ => (None, None),
        };
        root.push(Accessor {
            buffer_view: Some(view),
            byte_offset: None,
            count: USize64::from(count),
            component_type: Checked::Valid(GenericComponentType(data.component())),
            extensions: None,
            extras: Default::default(),
            type_: Checked::Valid(type_),
            min: min.and_then(Result::ok),
            max: max.and_then(Result::ok),
            name: None,
            normalized: false,
            sparse: None,
        })
    }

    /// Declares the buffer (the GLB's binary chunk) in `root`.
    pub fn declare(&self, root: &mut Root) {
        root.push(json::Buffer {
            byte_length: USize64::from(self.bytes.len()),
            name: None,
            uri: None,
            extensions: None,
            extras: Default::default(),
        });
    }
}

/// The GLB container: a 12-byte header, the JSON chunk padded with spaces,
/// the binary chunk padded with zeros.
pub fn glb_bytes(json_text: &[u8], bin: &[u8]) -> Vec<u8> {
    let pad = |n: usize| (4 - n % 4) % 4;
    let json_len = json_text.len() + pad(json_text.len());
    let bin_len = bin.len() + pad(bin.len());
    let total = 12 + 8 + json_len + if bin.is_empty() { 0 } else { 8 + bin_len };
    let mut out = Vec::with_capacity(total);
    out.extend(b"glTF");
    out.extend(2u32.to_le_bytes());
    out.extend((total as u32).to_le_bytes());
    out.extend((json_len as u32).to_le_bytes());
    out.extend(b"JSON");
    out.extend(json_text);
    out.resize(out.len() + pad(json_text.len()), b' ');
    if !bin.is_empty() {
        out.extend((bin_len as u32).to_le_bytes());
        out.extend(b"BIN\0");
        out.extend(bin);
        out.resize(out.len() + pad(bin.len()), 0);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_glb_is_aligned_and_says_its_length() {
        let glb = glb_bytes(b"{\"a\":1}", &[1, 2, 3, 4, 5]);
        assert_eq!(&glb[0..4], b"glTF");
        assert_eq!(
            u32::from_le_bytes(glb[8..12].try_into().unwrap()) as usize,
            glb.len()
        );
        assert_eq!(glb.len() % 4, 0);
        let json_len = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
        assert_eq!(json_len, 8);
        assert_eq!(&glb[20 + json_len + 4..20 + json_len + 8], b"BIN\0");
    }

    #[test]
    fn an_accessor_has_its_bounds_and_an_aligned_view() {
        let mut root = Root::default();
        let mut bin = BinBuffer::default();
        bin.accessor(
            &mut root,
            Elements::U16(&[1, 2, 3]),
            Type::Scalar,
            None,
            false,
        );
        let a = bin.accessor(
            &mut root,
            Elements::F32(&[1.0, -2.0, 3.0, -1.0, 5.0, 0.0]),
            Type::Vec3,
            Some(Target::ArrayBuffer),
            true,
        );
        let accessor = &root.accessors[a.value()];
        assert_eq!(accessor.count.0, 2);
        assert_eq!(
            accessor.min.as_ref().unwrap().to_string(),
            "[-1.0,-2.0,0.0]"
        );
        assert_eq!(root.buffer_views[1].byte_offset.unwrap().0, 8);
    }
}
