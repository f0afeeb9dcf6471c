use klaw::*;
fn main() {
    let body = Body::standard(1.8, 80.0).unwrap();
    let attrs = Attributes::default();
    let v: f64 = std::env::args().nth(1).map(|s| s.parse().unwrap()).unwrap_or(1.4);
    let gait = GaitRequest { velocity: Some(v), ..Default::default() }.complete(&body, &attrs).unwrap();
    let mut w = walk::Walker::new(body, attrs);
    for _ in 0..10 {
        match w.step(gait) {
            Ok(s) => {
                let st = &s.stance;
                let mut ymax: f64 = 0.0; let mut ymin: f64 = 9.0;
                for i in 0..=200 { let t = st.t_end()*i as f64/200.0; let h = st.hip(&s.stance_setup, t); ymax = ymax.max(h[0][1]); ymin = ymin.min(h[0][1]); }
                println!("step {} tau1 {:.3} p {:.5} {:?} impact {:.3} exc {:.4} (e {:.4}) below {:.2e} segs {}", s.index, st.tau1, st.p, s.solves[0].report, s.impact.speed_ratio, ymax - s.constraints.hip[1], s.constraints.bounce, s.constraints.hip[1].min(s.stance_setup.y_start) - ymin, st.segments.len());
            }
            Err(e) => { println!("error {e}"); break; }
        }
    }
}
