//! The REMUS 100's parameters: T. Prestero, "Verification of a six-degree of freedom simulation
//! model for the REMUS autonomous underwater vehicle", MIT/WHOI MS thesis, 2001 (cited below as
//! "Prestero", with his table numbers). The thesis itself was not at hand. Each value is as
//! transcribed from his tables in public implementations, and we cross-checked them:
//!
//! - \[A\] a transcription of Prestero's Appendix C tables with his component split (body lift,
//!   added mass, fin lift) and his REMUS.m listing (thesis p. 117), in public MATLAB copies of
//!   that listing (`remus.m`, "REMUS.M Vehicle Simulator").
//! - \[B\] ArizaWilmerUTAS/Path-Following `REMUS.m` (Prestero's Appendix B totals).
//! - \[C\] D. Sgarioto's "REMUS Hydrodynamic Coefficients" (DTA, 2006), in R. Hall and S. Anstee,
//!   "Trim calculation methods for a dynamical model of the REMUS 100 AUV".
//! - \[D\] a public reproduction of the thesis's model (`remus_rig.py` and its README). It lists the
//!   thesis's internal inconsistencies and which reading it took.
//! - \[F\] Fossen's REMUS 100 model (MSS `remus100.m`, Python Vehicle Simulator `remus100.py`).
//!   It uses its own spheroid-based coefficients, so we took only structure and limits from it.
//!
//! Signs follow Fossen's hydrodynamic-derivative convention (SNAME): X_u̇ < 0 and so on. The
//! origin of the body frame is the centre of buoyancy (Prestero's choice).

/// Top speed of the REMUS 100 in still water, m/s (Fossen 2021, §8.4; \[F\]: "the maximum speed
/// of 2.5 m/s"). The default thrust limit is the axial drag at this speed.
pub const MAX_SPEED: f64 = 2.5;

/// Every coefficient of the 6-DoF model, in SI units, body frame at the centre of buoyancy.
///
/// The added-mass cross terms of Prestero's Tables C.6–C.8 (X_wq, Y_wp, M_uwa = the Munk
/// moment, …) are not stored. The model gets them from the skew-symmetric C_A(ν_r) of the
/// added-mass matrix (Fossen's m2c), which reproduces every printed value. The exceptions are
/// M_rp and N_pq: C_A gives K_ṗ − N_ṙ = 4.81 where Prestero prints 4.86, because his Table C.8
/// predates his adjusted K_ṗ (\[D\]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Coefficients {
    /// m, kg.
    pub mass: f64,
    /// g, m/s².
    pub gravity: f64,
    /// B, N (buoyancy; the weight is W = m·g).
    pub buoyancy: f64,
    /// Centre of gravity r_g relative to the body origin (the centre of buoyancy), m.
    pub r_g: [f64; 3],
    /// Centre of buoyancy r_b relative to the body origin, m.
    pub r_b: [f64; 3],
    /// Principal moments of inertia about the origin [I_xx, I_yy, I_zz], kg·m².
    pub inertia: [f64; 3],
    /// Added mass X_u̇, kg.
    pub x_udot: f64,
    /// Added mass Y_v̇, kg.
    pub y_vdot: f64,
    /// Added mass Y_ṙ, kg·m/rad.
    pub y_rdot: f64,
    /// Added mass Z_ẇ, kg.
    pub z_wdot: f64,
    /// Added mass Z_q̇, kg·m/rad.
    pub z_qdot: f64,
    /// Added inertia K_ṗ, kg·m²/rad.
    pub k_pdot: f64,
    /// Added mass M_ẇ, kg·m.
    pub m_wdot: f64,
    /// Added inertia M_q̇, kg·m²/rad.
    pub m_qdot: f64,
    /// Added mass N_v̇, kg·m.
    pub n_vdot: f64,
    /// Added inertia N_ṙ, kg·m²/rad.
    pub n_rdot: f64,
    /// Axial drag X_u|u|, kg/m.
    pub x_uu: f64,
    /// Crossflow drag Y_v|v|, kg/m.
    pub y_vv: f64,
    /// Crossflow drag Y_r|r|, kg·m/rad².
    pub y_rr: f64,
    /// Crossflow drag Z_w|w|, kg/m.
    pub z_ww: f64,
    /// Crossflow drag Z_q|q|, kg·m/rad².
    pub z_qq: f64,
    /// Rolling resistance K_p|p|, kg·m²/rad².
    pub k_pp: f64,
    /// Crossflow drag moment M_w|w|, kg.
    pub m_ww: f64,
    /// Crossflow drag M_q|q|, kg·m²/rad².
    pub m_qq: f64,
    /// Crossflow drag moment N_v|v|, kg.
    pub n_vv: f64,
    /// Crossflow drag N_r|r|, kg·m²/rad².
    pub n_rr: f64,
    /// Body lift Y_uvl, kg/m.
    pub y_uv_body: f64,
    /// Body lift Z_uwl, kg/m.
    pub z_uw_body: f64,
    /// Body lift moment M_uwl, kg.
    pub m_uw_body: f64,
    /// Body lift moment N_uvl, kg.
    pub n_uv_body: f64,
    /// Fin lift from sideslip Y_uvf, kg/m.
    pub y_uv_fin: f64,
    /// Fin lift from angle of attack Z_uwf, kg/m.
    pub z_uw_fin: f64,
    /// Fin lift from yaw rate Y_urf, kg/rad.
    pub y_ur_fin: f64,
    /// Fin lift from pitch rate Z_uqf, kg/rad.
    pub z_uq_fin: f64,
    /// Fin lift moment M_uwf, kg.
    pub m_uw_fin: f64,
    /// Fin lift moment N_uvf, kg.
    pub n_uv_fin: f64,
    /// Fin lift moment M_uqf, kg·m/rad.
    pub m_uq_fin: f64,
    /// Fin lift moment N_urf, kg·m/rad.
    pub n_ur_fin: f64,
    /// Rudder lift Y_uuδr, kg/(m·rad).
    pub y_uu_dr: f64,
    /// Stern-plane lift Z_uuδs, kg/(m·rad).
    pub z_uu_ds: f64,
    /// Stern-plane moment M_uuδs, kg/rad.
    pub m_uu_ds: f64,
    /// Rudder moment N_uuδr, kg/rad.
    pub n_uu_dr: f64,
    /// Propeller thrust at Prestero's trial point (1500 rpm), X_prop, N.
    pub nominal_thrust: f64,
    /// Propeller roll torque at that point, K_prop, N·m. The model scales it with the thrust:
    /// K = K_prop / X_prop · thrust.
    pub nominal_prop_torque: f64,
}

impl Default for Coefficients {
    fn default() -> Self {
        Coefficients::prestero()
    }
}

impl Coefficients {
    /// Prestero's REMUS 100 (Tables 4.1 and C.1–C.10, Appendix B).
    pub fn prestero() -> Coefficients {
        Coefficients {
            // Table 4.1: m = 30.51 kg, the planner's default (scenario `Auv::default`). [A] and
            // [C] use W/g = 30.48 kg; W = m·g = 299.3 N here vs the printed W = 2.99e2 N.
            mass: 30.51,
            gravity: 9.81, // [A], [C], [D]
            // Table 2.3: B = 306 N, about 1.5 lbf (6.7 N) positively buoyant, as Prestero's
            // Sections 2.4 and 7.4.2 ballast it ([D]). Table A.1 and [A] print 308 N, and [C]
            // uses W + 0.75 lbf. We chose 306 N, following the reproduction [D].
            buoyancy: 306.0,
            // Table A.4: CG 1.96 cm below the CB (the origin); [A], [B], [C], [D] agree.
            r_g: [0.0, 0.0, 1.96e-2],
            r_b: [0.0, 0.0, 0.0],
            // Table 4.1 / A.1: I_xx = 0.177, I_yy = I_zz = 3.45 kg·m² ([A]–[D] agree; the
            // planner's I_zz = 3.45).
            inertia: [1.77e-1, 3.45, 3.45],
            // Table C.5 added mass ([A], [B], [C] agree; the planner's X_u̇, Z_ẇ, N_ṙ):
            x_udot: -9.30e-1,
            y_vdot: -3.55e1,
            y_rdot: 1.93,
            z_wdot: -3.55e1,
            z_qdot: -1.93,
            // K_ṗ = −7.04e−2 is Prestero's adjusted value (Table 8.2), as in [A], [B], [C].
            k_pdot: -7.04e-2,
            m_wdot: -1.93,
            m_qdot: -4.88,
            n_vdot: 1.93,
            n_rdot: -4.88,
            // Section 4.2.1 / Table B.1: X_u|u| = −1.62 kg/m ([A]–[D], the planner). With
            // X_prop = 3.86 N it gives Prestero's 1.54 m/s.
            x_uu: -1.62,
            // Table B.1 / C.2 crossflow drag. Y_v|v| = −1.31e3 is as printed in [A], [B], [C]
            // and one more public copy. It is ten times Z_w|w| although the hull is
            // axisymmetric; we read it as Prestero's Table 8.2 adjustment (×10) applied to
            // sway only ([D] notes B.1 leaves Z_w|w| unadjusted). One public copy uses −131
            // for both, and [C] uses −1310 for both. We keep the printed pair, which matches
            // the planner's Z_w|w| = −131.
            y_vv: -1.31e3,
            y_rr: 6.32e-1,
            z_ww: -1.31e2,
            z_qq: -6.32e-1,
            // Table C.3 rolling resistance ([A]–[D]).
            k_pp: -1.30e-1,
            m_ww: 3.18,
            // M_q|q| = −188 is 20 × the raw −9.40; Table 8.2 says 12.5× (−117.5). We kept
            // Appendix B's −188, as [A]–[D] do.
            m_qq: -1.88e2,
            n_vv: -3.18,
            n_rr: -9.40e1, // the planner's N_r|r| = −94
            // Table C.4 body lift and moment ([A]; [C]'s lift formulas give the same moment).
            y_uv_body: -2.86e1,
            z_uw_body: -2.86e1,
            m_uw_body: -4.47,
            n_uv_body: 4.47,
            // Table C.10 fin lift from the flow at the fins. Y_uvf = Z_uwf = −9.64 kg/m in
            // C.10, but Table B.1's totals Y_uv = Z_uw = −28.6 are body lift alone ([D]: eq.
            // (4.48) would give −38.2), and Prestero's simulations and [A]–[C] use −28.6. We
            // follow B.1 and set them to 0. The moment totals (B.1) do include the fin terms:
            // M_uw = 34.6 (Munk, from C_A) − 4.47 − 6.15 = 24.0 and N_uv = −24.0; Y_ur = −0.93
            // + 6.15 = 5.22, Z_uq = −5.22, M_uq = N_ur = 1.93 − 3.93 = −2.0, as [A]–[C] print.
            y_uv_fin: 0.0,
            z_uw_fin: 0.0,
            y_ur_fin: 6.15,
            z_uq_fin: -6.15,
            m_uw_fin: -6.15,
            n_uv_fin: 6.15,
            m_uq_fin: -3.93,
            n_ur_fin: -3.93,
            // Table C.10 control fins ([A], [B], [C]). N_uuδr = −6.15 = x_fin·Y_uuδr with the
            // fin post at x_fin = −0.638 m (Table 2.2): a positive rudder pushes the tail to
            // starboard and turns the nose to port. One public copy prints +6.15; that sign
            // contradicts Y_uuδr and x_fin.
            y_uu_dr: 9.64,
            z_uu_ds: -9.64,
            m_uu_ds: -6.15,
            n_uu_dr: -6.15,
            // Table C.9 propeller at 1500 rpm ([A]; [D] checks the −5.3° roll it gives).
            nominal_thrust: 3.86,
            nominal_prop_torque: -5.43e-1,
        }
    }

    /// The same vehicle in an ideal fluid: drag, lift, fin and propeller coefficients zero, and
    /// B = W with r_b = r_g so that g(η) = 0. Only M_RB, M_A, C_RB and C_A act, so kinetic
    /// energy and the Kirchhoff impulses are conserved.
    pub fn ideal_fluid(&self) -> Coefficients {
        let mut c = *self;
        for k in [
            &mut c.x_uu,
            &mut c.y_vv,
            &mut c.y_rr,
            &mut c.z_ww,
            &mut c.z_qq,
            &mut c.k_pp,
            &mut c.m_ww,
            &mut c.m_qq,
            &mut c.n_vv,
            &mut c.n_rr,
            &mut c.y_uv_body,
            &mut c.z_uw_body,
            &mut c.m_uw_body,
            &mut c.n_uv_body,
            &mut c.y_uv_fin,
            &mut c.z_uw_fin,
            &mut c.y_ur_fin,
            &mut c.z_uq_fin,
            &mut c.m_uw_fin,
            &mut c.n_uv_fin,
            &mut c.m_uq_fin,
            &mut c.n_ur_fin,
            &mut c.y_uu_dr,
            &mut c.z_uu_ds,
            &mut c.m_uu_ds,
            &mut c.n_uu_dr,
            &mut c.nominal_prop_torque,
        ] {
            *k = 0.0;
        }
        c.buoyancy = c.weight();
        c.r_b = c.r_g;
        c
    }

    /// W = m·g, N.
    pub fn weight(&self) -> f64 {
        self.mass * self.gravity
    }

    /// Propeller roll torque per newton of thrust, K_prop / X_prop, m (0 if X_prop is 0).
    pub fn prop_torque_per_thrust(&self) -> f64 {
        if self.nominal_thrust != 0.0 {
            self.nominal_prop_torque / self.nominal_thrust
        } else {
            0.0
        }
    }

    /// Axial drag −X_u|u|·u|u| in straight, level flight at surge speed `u` through still water, N
    /// (positive against forward motion). Prestero's model has no fin drag at zero fin angle.
    pub fn surge_drag(&self, u: f64) -> f64 {
        -self.x_uu * u * u.abs()
    }

    /// All values in one list (for validation).
    pub(super) fn all(&self) -> Vec<f64> {
        let c = self;
        let mut v = vec![c.mass, c.gravity, c.buoyancy];
        v.extend(c.r_g);
        v.extend(c.r_b);
        v.extend(c.inertia);
        v.extend([
            c.x_udot,
            c.y_vdot,
            c.y_rdot,
            c.z_wdot,
            c.z_qdot,
            c.k_pdot,
            c.m_wdot,
            c.m_qdot,
            c.n_vdot,
            c.n_rdot,
            c.x_uu,
            c.y_vv,
            c.y_rr,
            c.z_ww,
            c.z_qq,
            c.k_pp,
            c.m_ww,
            c.m_qq,
            c.n_vv,
            c.n_rr,
            c.y_uv_body,
            c.z_uw_body,
            c.m_uw_body,
            c.n_uv_body,
            c.y_uv_fin,
            c.z_uw_fin,
            c.y_ur_fin,
            c.z_uq_fin,
            c.m_uw_fin,
            c.n_uv_fin,
            c.m_uq_fin,
            c.n_ur_fin,
            c.y_uu_dr,
            c.z_uu_ds,
            c.m_uu_ds,
            c.n_uu_dr,
            c.nominal_thrust,
            c.nominal_prop_torque,
        ]);
        v
    }
}
