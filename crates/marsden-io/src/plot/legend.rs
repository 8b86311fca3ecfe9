//! Legends that fit: at most [`MAX_LEGEND`] entries, then one saying how many more curves
//! there are (an N-body run of 64 bodies once listed all 64, past the bottom of the picture).

use super::render::Panel;

/// Most legend entries drawn per panel; the curves after them are drawn unlabelled.
pub const MAX_LEGEND: usize = 8;

/// Keeps the labels of the first [`MAX_LEGEND`] labelled lines of `panel` and drops the
/// others' (the curves are still drawn), recording how many were dropped in
/// [`Panel::legend_more`] (drawn as a last entry `… 56 more`) and in a note.
pub(crate) fn cap_legend(panel: &mut Panel) {
    let labelled = panel.lines.iter().filter(|l| l.label.is_some()).count();
    if labelled <= MAX_LEGEND {
        return;
    }
    let mut kept = 0;
    for line in &mut panel.lines {
        if line.label.is_some() {
            kept += 1;
            if kept > MAX_LEGEND {
                line.label = None;
            }
        }
    }
    panel.legend_more = labelled - MAX_LEGEND;
    panel.notes.push(format!(
        "the legend names the first {MAX_LEGEND} of {labelled} curves"
    ));
}

/// The last legend entry for `more` unlabelled curves.
pub(crate) fn more_text(more: usize) -> String {
    format!("… {more} more")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::downsample::Segments;
    use crate::plot::render::Line;

    fn panel_of(labels: usize, unlabelled: usize) -> Panel {
        let mut panel = Panel::new("", "x", "y");
        let line = |label: Option<String>| Line {
            label,
            data: Segments::default(),
        };
        panel
            .lines
            .extend((0..labels).map(|i| line(Some(format!("body {i}")))));
        panel.lines.extend((0..unlabelled).map(|_| line(None)));
        panel
    }

    /// 64 bodies: the first 8 keep their names, 56 more are counted and noted.
    #[test]
    fn a_legend_of_64_bodies_names_8_and_counts_the_rest() {
        let mut panel = panel_of(64, 1);
        cap_legend(&mut panel);
        let names: Vec<&str> = panel
            .lines
            .iter()
            .filter_map(|l| l.label.as_deref())
            .collect();
        assert_eq!(names.len(), 8);
        assert_eq!(names[7], "body 7");
        assert_eq!(panel.lines.len(), 65, "every curve is still drawn");
        assert_eq!(panel.legend_more, 56);
        assert_eq!(more_text(panel.legend_more), "… 56 more");
        assert_eq!(panel.notes, ["the legend names the first 8 of 64 curves"]);
    }

    /// A legend of eight is left alone.
    #[test]
    fn a_short_legend_is_unchanged() {
        let mut panel = panel_of(8, 0);
        cap_legend(&mut panel);
        assert_eq!(panel.legend_more, 0);
        assert!(panel.notes.is_empty());
        assert!(panel.lines.iter().all(|l| l.label.is_some()));
    }
}
