//! The texts the command prints, built here so that every front end shows the same words:
//! [`run`] (the summary of a run), [`check`] (the resolved problem), [`systems`] (the
//! catalog). The sweep table is [`crate::run::sweep_table`], the order-study table
//! [`crate::order_study::table`].

pub mod check;
pub mod run;
pub mod systems;
