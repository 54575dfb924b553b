//! A live view in the tev HDR viewer (`ptsc render --tev`), as pbrt-v4's
//! `--display-server`: the image is created in tev over its TCP protocol,
//! then sent again after every pass.
//!
//! The protocol (tev's `src/Ipc.cpp`, its Python client `ipc.py`): each
//! packet is a little-endian u32, the packet's length in bytes (these four
//! included), a type byte, then its fields; strings end with a 0 byte,
//! integers are little-endian.
//!
//! - create image (4): grab focus (u8), name, width, height and channel
//!   count (i32), the channels' names;
//! - update image (6): grab focus (u8), name, channel count (i32), the
//!   channels' names, the tile's x, y, width and height (i32), each
//!   channel's offset and stride into the data in floats (i64), then the
//!   tile's pixels as f32, channels interleaved, row by row.

use glam::Vec3;
use std::io::Write;
use std::net::{TcpStream, ToSocketAddrs};
use std::time::Duration;

/// Where tev listens unless told otherwise.
pub const DEFAULT_ADDRESS: &str = "127.0.0.1:14158";

/// Packet types of tev's protocol.
const CREATE_IMAGE: u8 = 4;
const UPDATE_IMAGE: u8 = 6;

/// Side of the tiles an image is sent in (tev's own client's choice: a
/// packet of 192 KiB at most).
const TILE: u32 = 128;

/// The channels sent.
const CHANNELS: [&str; 3] = ["R", "G", "B"];

/// An image open in tev.
pub struct Tev {
    stream: TcpStream,
    name: String,
    size: (u32, u32),
}

impl Tev {
    /// Connects to tev at `address` (`HOST:PORT`) and creates the image
    /// `name` of `size`, black; why not, as a sentence.
    pub fn open(address: &str, name: &str, size: (u32, u32)) -> Result<Tev, String> {
        let unreachable = |why: String| {
            format!("cannot reach tev at {address} ({why}): start tev first, or name where it listens (--tev HOST:PORT)")
        };
        let addresses = address
            .to_socket_addrs()
            .map_err(|e| unreachable(e.to_string()))?;
        let mut last = "no address".to_string();
        for a in addresses {
            match TcpStream::connect_timeout(&a, Duration::from_secs(2)) {
                Ok(stream) => {
                    let _ = stream.set_write_timeout(Some(Duration::from_secs(10)));
                    let mut tev = Tev {
                        stream,
                        name: name.replace('\0', ""),
                        size,
                    };
                    tev.create().map_err(|e| unreachable(e.to_string()))?;
                    return Ok(tev);
                }
                Err(e) => last = e.to_string(),
            }
        }
        Err(unreachable(last))
    }

    /// Sends the create-image packet.
    fn create(&mut self) -> std::io::Result<()> {
        let mut p = Packet::new(CREATE_IMAGE);
        p.byte(1).text(&self.name);
        p.int(self.size.0 as i32).int(self.size.1 as i32).int(3);
        CHANNELS.iter().for_each(|c| _ = p.text(c));
        self.stream.write_all(&p.finish())
    }

    /// Sends the image whose pixel `i` (row-major) is `pixel(i)`, tile by
    /// tile.
    pub fn show(&mut self, pixel: impl Fn(usize) -> Vec3) -> std::io::Result<()> {
        let (w, h) = self.size;
        for y0 in (0..h).step_by(TILE as usize) {
            for x0 in (0..w).step_by(TILE as usize) {
                let (tw, th) = (TILE.min(w - x0), TILE.min(h - y0));
                let mut p = Packet::new(UPDATE_IMAGE);
                p.byte(0).text(&self.name).int(3);
                CHANNELS.iter().for_each(|c| _ = p.text(c));
                p.int(x0 as i32)
                    .int(y0 as i32)
                    .int(tw as i32)
                    .int(th as i32);
                (0..3).for_each(|c| _ = p.long(c));
                (0..3).for_each(|_| _ = p.long(3));
                for y in y0..y0 + th {
                    for x in x0..x0 + tw {
                        let v = pixel((y * w + x) as usize);
                        v.to_array().iter().for_each(|&f| _ = p.float(f));
                    }
                }
                self.stream.write_all(&p.finish())?;
            }
        }
        self.stream.flush()
    }
}

/// A packet being written: its length is filled in at the end.
struct Packet(Vec<u8>);

impl Packet {
    fn new(kind: u8) -> Packet {
        Packet(vec![0, 0, 0, 0, kind])
    }
    fn byte(&mut self, b: u8) -> &mut Packet {
        self.0.push(b);
        self
    }
    fn text(&mut self, s: &str) -> &mut Packet {
        self.0.extend_from_slice(s.as_bytes());
        self.byte(0)
    }
    fn int(&mut self, v: i32) -> &mut Packet {
        self.0.extend_from_slice(&v.to_le_bytes());
        self
    }
    fn long(&mut self, v: i64) -> &mut Packet {
        self.0.extend_from_slice(&v.to_le_bytes());
        self
    }
    fn float(&mut self, v: f32) -> &mut Packet {
        self.0.extend_from_slice(&v.to_le_bytes());
        self
    }
    fn finish(mut self) -> Vec<u8> {
        let n = self.0.len() as u32;
        self.0[..4].copy_from_slice(&n.to_le_bytes());
        self.0
    }
}
