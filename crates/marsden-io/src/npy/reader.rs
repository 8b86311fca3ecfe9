//! Reading `.npy` files back (through the `npyz` crate).

use std::fs::File;
use std::io::BufReader;
use std::path::Path;

use crate::error::{Error, Result};

/// A numeric array read from a `.npy` file: its shape and its values in C (row-major) order.
#[derive(Debug, Clone, PartialEq)]
pub struct NpyArray {
    /// The array's dtype as written in the header, e.g. `<f8`.
    pub dtype: String,
    /// The shape, e.g. `[rows]` or `[rows, columns]`.
    pub shape: Vec<u64>,
    /// All values, row after row.
    pub data: Vec<f64>,
}

/// Reads a `.npy` file of `f64` values (any byte order), C order.
///
/// # Errors
/// An I/O error naming `path`, or [`Error::Npy`] for a non-`f64` dtype, Fortran order, or a
/// file shorter than its header says.
pub fn read_npy(path: impl AsRef<Path>) -> Result<NpyArray> {
    let path = path.as_ref();
    let (npy, dtype) = open_npy(path)?;
    let shape = npy.shape().to_vec();
    let data = npy
        .into_vec::<f64>()
        .map_err(|e| npy_error(path, format!("cannot read data: {e}")))?;
    Ok(NpyArray { dtype, shape, data })
}

/// Values of a `.npy` file read one at a time, for streaming a long array.
pub(crate) struct NpyValues {
    pub shape: Vec<u64>,
    values: npyz::NpyReader<f64, BufReader<File>>,
    path: std::path::PathBuf,
}

impl NpyValues {
    /// Opens `path` and checks its header as [`read_npy`] does.
    pub(crate) fn open(path: &Path) -> Result<Self> {
        let (npy, _) = open_npy(path)?;
        let shape = npy.shape().to_vec();
        let values = npy
            .data::<f64>()
            .map_err(|e| npy_error(path, format!("cannot read data: {e}")))?;
        Ok(Self {
            shape,
            values,
            path: path.to_path_buf(),
        })
    }

    /// The next value; a file shorter than its header says is an error.
    pub(crate) fn next_value(&mut self) -> Result<f64> {
        match self.values.next() {
            Some(Ok(v)) => Ok(v),
            Some(Err(e)) => Err(npy_error(&self.path, format!("cannot read data: {e}"))),
            None => Err(npy_error(
                &self.path,
                "file shorter than its header says".into(),
            )),
        }
    }
}

fn npy_error(path: &Path, message: String) -> Error {
    Error::Npy {
        path: path.to_path_buf(),
        message,
    }
}

/// Opens a `.npy` file and checks it holds `f64` values in C order; returns it and its dtype.
fn open_npy(path: &Path) -> Result<(npyz::NpyFile<BufReader<File>>, String)> {
    let npy_err = |message: String| npy_error(path, message);
    let file = File::open(path).map_err(|e| Error::io("open", path, e))?;
    let npy = npyz::NpyFile::new(BufReader::new(file))
        .map_err(|e| npy_err(format!("bad .npy header: {e}")))?;
    let dtype = match npy.dtype() {
        npyz::DType::Plain(ts) => ts.to_string(),
        other => return Err(npy_err(format!("unsupported dtype {}", other.descr()))),
    };
    if !matches!(dtype.as_str(), "<f8" | ">f8") {
        return Err(npy_err(format!("dtype is {dtype}, expected <f8")));
    }
    if npy.order() == npyz::Order::Fortran && npy.shape().len() > 1 {
        return Err(npy_err("Fortran-order arrays are not supported".into()));
    }
    Ok((npy, dtype))
}
