//! Writing and reading a study: one CSV per study, `speed.json`, and the figures.

use super::*;

impl SpeedStudy {
    /// The study as JSON (read back by the scorecard), relative to the study's folder.
    pub const JSON: &'static str = "speed.json";
    /// Folder of the tables and figures, relative to the study's folder.
    pub const FIGURES: &'static str = "speed";
    /// The tables, one per study: `speed/<name>.csv`.
    pub const TABLES: [&'static str; 6] =
        ["reference", "tolerance", "size", "threads", "floor", "warm"];

    /// The table of study `name` (one of [`SpeedStudy::TABLES`]) in the study's folder `dir`.
    pub fn table_path(dir: &Path, name: &str) -> PathBuf {
        dir.join(Self::FIGURES).join(format!("{name}.csv"))
    }

    /// Writes one CSV per study (under `speed/`), `speed.json` and the figures (under
    /// `speed/`) into `dir`; returns the paths written.
    pub fn write(&self, dir: &Path) -> Result<Vec<PathBuf>> {
        let mut written = Vec::new();
        let [reference, tolerance, size, threads, floor, warm] = Self::TABLES;
        written.push(write_rows(
            dir,
            reference,
            std::slice::from_ref(&self.reference),
        )?);
        written.push(write_rows(dir, tolerance, &self.tolerance)?);
        written.push(write_rows(dir, size, &self.sizes)?);
        written.push(write_rows(dir, threads, &self.threads_study)?);
        written.push(write_rows(dir, floor, &self.floor)?);
        written.push(write_rows(dir, warm, &self.warm)?);
        let json_path = dir.join(Self::JSON);
        let json = serde_json::to_vec_pretty(self).expect("the study serialises");
        crate::io::write_atomic(&json_path, &json)?;
        written.push(json_path);
        for figure in self.figures() {
            written.extend(crate::plot::render(&figure, &dir.join(Self::FIGURES))?);
        }
        Ok(written)
    }

    /// Reads a study written by [`SpeedStudy::write`].
    pub fn read(path: &Path) -> Result<Self> {
        let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
        serde_json::from_slice(&bytes).map_err(|e| Error::bad_file(path, e.to_string()))
    }

    /// The study's figures: energy error against time (the contact-area error, quantised in
    /// steps of `1/N^2`, is in the table), and iterations against grid size.
    pub fn figures(&self) -> Vec<Figure> {
        let mut error_fig = Figure {
            name: "speed_error".into(),
            title: format!(
                "Error against wall time, N = {}, cold solves at tolerances {}",
                self.options.n,
                self.options
                    .tols
                    .iter()
                    .map(|t| format!("{t:e}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            x: Axis::log("wall time (s)"),
            y: Axis::log("relative energy error |E - E_ref| / E_ref"),
            y2: None,
            series: Vec::new(),
        };
        for kind in SOLVERS {
            let pts: Vec<(f64, f64)> = self
                .tolerance
                .iter()
                .filter(|r| r.solver == kind)
                .filter_map(|r| Some((r.wall_s?, r.energy_error?)))
                .collect();
            error_fig
                .series
                .push(Series::xy(kind.name().to_string(), Style::LinePoints, pts));
        }
        let mut size_fig = Figure {
            name: "speed_iterations".into(),
            title: format!(
                "Iterations against grid size at tolerance {:e} (lambda_l = N/2, lambda_s = {})",
                self.options.size_tol, self.options.lambda_s
            ),
            x: Axis::log("points per side N"),
            y: Axis::log("iterations"),
            y2: None,
            series: Vec::new(),
        };
        for (kind, fit) in SOLVERS.iter().zip(&self.fits) {
            let rows: Vec<(f64, f64)> = self
                .sizes
                .iter()
                .filter(|r| r.solver == *kind)
                .filter_map(|r| Some((r.n as f64, r.iterations? as f64)))
                .collect();
            size_fig.series.push(Series::xy(
                kind.name().to_string(),
                Style::LinePoints,
                rows.clone(),
            ));
            if let (Some(k), Some(&(n0, _))) = (fit.exponent, rows.first()) {
                let last = rows.last().map_or(n0, |r| r.0);
                // The fitted power law through the geometric centre of the points.
                let (lx, ly): (f64, f64) = rows
                    .iter()
                    .fold((0.0, 0.0), |a, r| (a.0 + r.0.ln(), a.1 + r.1.ln()));
                let (cx, cy) = (lx / rows.len() as f64, ly / rows.len() as f64);
                let at = |n: f64| (cy + k * (n.ln() - cx)).exp();
                size_fig.series.push(Series::xy(
                    format!("{}: fit N^{k:.2}", kind.name()),
                    Style::Dashed,
                    [(n0, at(n0)), (last, at(last))],
                ));
            }
        }
        vec![error_fig, size_fig]
    }
}

/// Writes `rows` as the table `name` of the study in `dir` (a header from the row type's
/// fields, empty cells for absent values); returns its path.
fn write_rows<T: Serialize>(dir: &Path, name: &str, rows: &[T]) -> Result<PathBuf> {
    let path = SpeedStudy::table_path(dir, name);
    let to_io = |e: csv::Error| Error::io(&path, std::io::Error::other(e));
    let mut w = csv::Writer::from_writer(Vec::new());
    for row in rows {
        w.serialize(row).map_err(to_io)?;
    }
    let bytes = w
        .into_inner()
        .map_err(|e| Error::io(&path, std::io::Error::other(e.to_string())))?;
    crate::io::write_atomic(&path, &bytes)?;
    Ok(path)
}
