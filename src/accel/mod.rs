//! Acceleration structures: the binned-SAH BVH build, the 4-wide BVH that is
//! traversed, the blocks of four triangles in its leaves (the one place that
//! knows the "plain triangle" leaf format), the buffers they live in (2 MiB
//! pages for large trees), packets of coherent rays walked together and the
//! counters of rays traced.

pub mod bvh;
pub mod bvh4;
pub mod numbering;
pub mod packet;
pub mod pages;
pub mod ray_count;
pub mod tri4;
