// SPDX-License-Identifier: Apache-2.0
// svpwm_duty: the compute path -- a voltage reference in any input mode -> sector and dwell times ->
// hexagon clamp -> three compare values (AVR495 Table 4-3) -> zero-vector placement (SVPWM / DPWM).
// Modes (mode_i): 0 FREQ  sector + angle from the phase accumulator, magnitude m_i
//                 1 VF    as FREQ, m = min(vf_mmax, vf_boost + |f| * vf_slope)  (AVR495 V/f law)
//                 2 POLAR angle theta_i (2^16 = 360 deg) + magnitude m_i
//                 3 AB    v_alpha = v1_i, v_beta = v2_i, sector and dwell times without trigonometry
//                 4 DQ    v_d = v1_i, v_q = v2_i, angle theta_i: inverse Park in the sector frame
//                 5..7    invalid: the zero vector (all phases 50 %) and err_o
// Polar path: T1 = m sin(60 - theta'), T2 = m sin(theta') (Minas eq. (4), AVR495 sec. 4.2) from the 0..60 deg
// sine_rom by linear interpolation. AB / DQ: projections X = v_beta, Y = (sqrt3 v_alpha + v_beta)/2,
// Z = (v_beta - sqrt3 v_alpha)/2; the sector is where q_s >= 0 > q_{s+1} for q = (X, Z, -Y, -X, -Z, Y),
// T2 = q_s, T1 = -q_{s+1} (Minas eq. (5) generalised). A vector beyond the hexagon (T1 + T2 > 1) is
// clamped to its boundary keeping the angle: min(T1, T2) is divided by T1 + T2 (restoring divider,
// 2 bits per clock), the other becomes 1 - q (sat_o). Arithmetic: exactly
// model/svpwm_model/fixed.py:modulate() (the golden model).
// One 16x16 multiplier (one iCE40 DSP) and the single-port ROM are time-shared by a fixed schedule.
// Parameters: CntWidth - period / compare width (8..16).
// Latency: DutyLatency = 34 clocks from start_i to done_o, the same in every mode; outputs hold until the
// next done_o (also across abort_i, which returns to idle without done_o). Restrictions: start_i is ignored
// while busy_o (abort_i first to restart).
`default_nettype none

module svpwm_duty #(
  parameter int CntWidth = 16
) (
  input  logic                  clk_i,        // core clock
  input  logic                  rst_ni,       // asynchronous reset, active low
  input  logic                  start_i,      // sample the inputs below and start
  input  logic                  abort_i,      // stop a computation (the core stopped): back to idle
  input  logic [2:0]            mode_i,       // input mode (above)
  input  logic [2:0]            sector_i,     // phase accumulator: sector 0..5 (FREQ, VF)
  input  logic [15:0]           angle_i,      // phase accumulator: theta' / 60 deg, UQ0.16 (FREQ, VF)
  input  logic [15:0]           theta_i,      // electrical angle, 2^16 = 360 deg (POLAR, DQ)
  input  logic [15:0]           m_i,          // magnitude, UQ1.15 (FREQ, POLAR)
  input  logic [15:0]           fabs_i,       // |frequency word| >> (FreqWidth - 17) (VF)
  input  logic signed [15:0]    v1_i,         // v_alpha or v_d, Q2.14 (AB, DQ)
  input  logic signed [15:0]    v2_i,         // v_beta or v_q, Q2.14 (AB, DQ)
  input  logic [15:0]           vf_boost_i,   // V/f: m at zero frequency, UQ1.15
  input  logic [15:0]           vf_slope_i,   // V/f: m LSBs per fabs_i LSB, UQ8.8
  input  logic [15:0]           vf_mmax_i,    // V/f: largest m, UQ1.15
  input  logic [1:0]            dpwm_i,       // 0 SVPWM, 1 DPWMMIN, 2 DPWMMAX, 3 DPWM1 (60 deg)
  input  logic [CntWidth-1:0]   period_i,     // half carrier period P the compare values are scaled to
  output logic                  busy_o,       // a computation is running
  output logic                  done_o,       // one-cycle pulse: the outputs below are new
  output logic [2:0]            sector_o,     // sector of the result
  output logic [3*CntWidth-1:0] cmp_o,        // {C_c, C_b, C_a}, each in [0, P]
  output logic                  sat_o,        // the reference was clamped to the hexagon
  output logic                  err_o         // invalid mode: zero vector
);

  localparam int KFrac  = 8;                     // fraction bits kept of P*d (model K_FRAC)
  localparam int KWidth = CntWidth + KFrac + 3;  // signed width of (P+1)*2^KFrac +- (A +- B)
  localparam int XW     = 22;                    // signed projections X, Y, Z and dwell sums
  localparam int LastSt = 33;                    // the schedule: steps 1 .. LastSt, done_o after it

  localparam logic [2:0] ModeFreq = 3'd0, ModeVf = 3'd1, ModePolar = 3'd2, ModeAb = 3'd3, ModeDq = 3'd4;
  localparam logic [15:0] Sqrt3Half = 16'd56756;        // round(sqrt(3)/2 * 2^16)
  localparam logic [XW-1:0] DOne = XW'(32'h1_0000);     // dwell time of a whole period

  if (CntWidth < 8 || CntWidth > 16) begin : gen_bad_width
    initial $fatal(1, "svpwm_duty: CntWidth must be 8..16, got %0d", CntWidth);
  end

  // ---- state -------------------------------------------------------------------------------------
  logic [5:0]            st_d, st_q;                        // 0 idle, 1..LastSt steps
  logic                  idle_d, idle_q;                    // st_q == 0, registered
  logic [2:0]            swq_d, swq_q;                      // projection index of the sector (AB, DQ)
  logic [2:0]            mode_d, mode_q, sec0_d, sec0_q, sector_d, sector_q, sector_out_d, sector_out_q;
  logic [1:0]            dpwm_d, dpwm_q;
  logic [15:0]           a16_d, a16_q, u16_d, u16_q;        // theta' and |theta' - 30 deg|, UQ0.16 of 60 deg
  logic [15:0]           m_d, m_q, fa_d, fa_q, boost_d, boost_q, slope_d, slope_q, mmax_d, mmax_q;
  logic signed [15:0]    v1_d, v1_q, v2_d, v2_q;
  logic [CntWidth-1:0]   p_d, p_q;
  logic [15:0]           r0_d, r0_q;                        // ROM sample held for the interpolation
  logic [15:0]           h_d, h_q, g_d, g_q, sb_d, sb_q, sa_d, sa_q, ct_d, ct_q, c60_d, c60_q;
  logic [XW-1:0]         x_d, x_q, y_d, y_q, z_d, z_q;      // signed projections (dwell units)
  logic [XW-1:0]         t1_d, t1_q, t2_d, t2_q;            // dwell times (unsigned values)
  logic [XW-1:0]         div_s_d, div_s_q, rem_d, rem_q;    // divisor T1 + T2, remainder
  logic [XW-1:0]         div3_d, div3_q;                    // 3 (T1 + T2)
  logic [15:0]           quo_d, quo_q;
  logic                  sat_d, sat_q, first_d, first_q, err_d, err_q, sat_out_d, sat_out_q,
                         err_out_d, err_out_q;
  logic [CntWidth+7:0]   b8_d, b8_q;                        // (T2 * P) >> 8
  logic [CntWidth+9:0]   sum_d, sum_q, dif_d, dif_q;        // A + B, A - B (signed)
  logic signed [CntWidth+1:0] sh_d, sh_q;                   // zero-vector shift of all three C
  logic [31:0]           prod_d, prod_q;                    // the shared multiplier's registered product
  logic [3*CntWidth-1:0] c_d, c_q, cmp_d, cmp_q;
  logic                  done_d, done_q;

  // ---- sine ROM ----------------------------------------------------------------------------------
  logic [8:0]  rom_addr;
  logic [15:0] rom_data;

  sine_rom u_rom (
    .clk_i  (clk_i),
    .addr_i (rom_addr),
    .data_o (rom_data)
  );

  // two interpolations: u = |theta' - 30| at steps 1..6 (h = sin u, g = sin(60 - u)), then theta' at
  // steps 5..10 (sb = sin theta', sa = sin(60 - theta')); each reads R[i], R[i+1], R[256-i], R[255-i]
  always_comb begin
    unique case (st_q)
      6'd1:    rom_addr = {1'b0, u16_q[15:8]};
      6'd2:    rom_addr = {1'b0, u16_q[15:8]} + 9'd1;
      6'd3:    rom_addr = 9'd256 - {1'b0, u16_q[15:8]};
      6'd4:    rom_addr = 9'd255 - {1'b0, u16_q[15:8]};
      6'd5:    rom_addr = {1'b0, a16_q[15:8]};
      6'd6:    rom_addr = {1'b0, a16_q[15:8]} + 9'd1;
      6'd7:    rom_addr = 9'd256 - {1'b0, a16_q[15:8]};
      6'd8:    rom_addr = 9'd255 - {1'b0, a16_q[15:8]};
      default: rom_addr = '0;
    endcase
  end

  // ---- shared multiplier: unsigned 16 x 16, signs handled outside (sign-magnitude) ----------------
  logic [15:0] mul_a, mul_b, v1_mag, v2_mag;
  logic        dq, ab, polar_like;

  assign v1_mag     = v1_q[15] ? 16'(-v1_q) : v1_q;
  assign v2_mag     = v2_q[15] ? 16'(-v2_q) : v2_q;
  assign dq         = mode_q == ModeDq;
  assign ab         = mode_q == ModeAb;
  assign polar_like = mode_q == ModeFreq || mode_q == ModeVf || mode_q == ModePolar;

  always_comb begin
    mul_a = '0;
    mul_b = '0;
    unique case (st_q)
      6'd2:  if (ab) begin mul_a = v1_mag; mul_b = Sqrt3Half; end         // sqrt3/2 |v_alpha|
      6'd3:  begin mul_a = rom_data - r0_q; mul_b = {8'd0, u16_q[7:0]}; end
      6'd4:  begin mul_a = fa_q; mul_b = slope_q; end                      // V/f: |f| * slope
      6'd5:  begin mul_a = r0_q - rom_data; mul_b = {8'd0, u16_q[7:0]}; end
      6'd7:  begin mul_a = rom_data - r0_q; mul_b = {8'd0, a16_q[7:0]}; end
      6'd8:  begin mul_a = v2_mag; mul_b = ct_q; end                       // |v_q| cos theta'
      6'd9:  begin mul_a = r0_q - rom_data; mul_b = {8'd0, a16_q[7:0]}; end
      6'd10: begin mul_a = dq ? v2_mag : m_q; mul_b = dq ? c60_q : sb_q; end  // |v_q| cos(60-t') | m sin t'
      6'd11: begin mul_a = dq ? v1_mag : m_q; mul_b = sb_q; end            // |v_d| sin t'    | m sin(60-t')
      6'd12: begin mul_a = v1_mag; mul_b = sa_q; end                       // |v_d| sin(60-t')
      6'd27: begin mul_a = t2_q[15:0]; mul_b = 16'(p_q); end               // T2 * P
      6'd28: begin mul_a = t1_q[15:0]; mul_b = 16'(p_q); end               // T1 * P
      default: ;
    endcase
    if (st_q == 6'd11 && !dq) mul_b = sa_q;
  end

  assign prod_d = mul_a * mul_b;

  // rounded scalings of the product: m * sin (>> 15); interpolation (>> 8) and voltage * trig (>> 14) only
  // inside a sum: a +- round(p >> k) = a +- ((p >> k) + p[k-1]) is one carry chain,
  // ({a, 1} + {(p >> k) ^ s, p[k-1] ^ s}) >> 1: the extra LSB column turns p[k-1] into the carry-in, and for
  // s = 1 it adds ~(p >> k) + !p[k-1] = -(p >> k) - p[k-1]
  logic [16:0] p_m;
  assign p_m = 17'((prod_q + 32'd16384) >> 15);

  function automatic logic [XW-1:0] add_rv(input logic [XW-1:0] a, input logic [17:0] ph, input logic b,
                                           input logic s);     // a +- round(p >> 14), p = {ph, b, ...}
    logic [XW:0] t;
    t      = {a, 1'b1} + {XW'(ph) ^ {XW{s}}, b ^ s};
    add_rv = t[XW:1];
  endfunction

  function automatic logic [15:0] add_ri(input logic [15:0] a, input logic [15:0] ph, input logic b,
                                         input logic s);       // a +- round(p >> 8) mod 2^16
    logic [16:0] t;
    t      = {a, 1'b1} + {ph ^ {16{s}}, b ^ s};
    add_ri = t[16:1];
  endfunction

  logic [17:0] pv_h;                                          // p >> 14 and the rounding bit
  logic        pv_b, pi_b;
  logic [15:0] pi_h;                                          // (p >> 8) mod 2^16 and the rounding bit
  assign pv_h = prod_q[31:14];
  assign pv_b = prod_q[13];
  assign pi_h = prod_q[23:8];
  assign pi_b = prod_q[7];

  // ---- sector from the projections (AB, DQ) ------------------------------------------------------
  // (continuous assignments throughout this and the next two sections: always_comb blocks that re-read
  // variables they assign more than once hung Icarus 11 in zero-delay loops)
  logic [5:0]    neg, hit;                                   // q_s < 0; q_s >= 0 > q_{s+1}
  logic [2:0]    sw, sw1, sw_sum;
  logic [3:0]    sw_add;

  // signs of q = (X, Z, -Y, -X, -Z, Y) without negating: -v < 0 exactly when v > 0
  assign neg = {y_q[XW-1], !z_q[XW-1] && (z_q != '0), !x_q[XW-1] && (x_q != '0),
                !y_q[XW-1] && (y_q != '0), z_q[XW-1], x_q[XW-1]};
  for (genvar gs = 0; gs < 6; gs++) begin : gen_hit
    assign hit[gs] = !neg[gs] && neg[(gs + 1) % 6];
  end
  // the first hit (none: all projections are 0, the zero vector: sector 0, T1 = T2 = 0)
  assign sw     = hit[0] ? 3'd0 : hit[1] ? 3'd1 : hit[2] ? 3'd2 : hit[3] ? 3'd3 : hit[4] ? 3'd4 :
                  hit[5] ? 3'd5 : 3'd0;
  assign sw_add = {1'b0, swq_q} + {1'b0, sec0_q};               // DQ: plus theta's own sector, mod 6
  assign sw_sum = !dq ? swq_q : (sw_add >= 4'd6) ? 3'(sw_add - 4'd6) : sw_add[2:0];
  // one step later, from |X|, |Y|, |Z|: T2 = q_s = |q_s| (q_s >= 0), T1 = -q_{s+1} = |q_{s+1}| (q_{s+1} < 0);
  // |q_k| is |X|, |Z|, |Y| for k mod 3 = 0, 1, 2
  assign sw1 = (swq_q == 3'd5) ? 3'd0 : swq_q + 3'd1;

  function automatic logic [XW-1:0] abs_xw(input logic [XW-1:0] v);
    abs_xw = v[XW-1] ? XW'(-v) : v;
  endfunction

  function automatic logic [XW-1:0] pick_q(input logic [2:0] k, input logic [XW-1:0] ax, input logic [XW-1:0] ay,
                                           input logic [XW-1:0] az);
    unique case (k)
      3'd0, 3'd3: pick_q = ax;
      3'd1, 3'd4: pick_q = az;
      default:    pick_q = ay;
    endcase
  endfunction

  // ---- divider step: two restoring steps per clock, as one radix-4 step with the three trial
  // subtractions in parallel: digit = floor(4 rem / d) in 0..3 (rem < d), rem' = 4 rem - digit * d
  logic [XW-1:0] r4;
  logic [XW:0]   s1, s2, s3;                                 // 4 rem - d, - 2d, - 3d (borrow in the MSB)
  logic          ge1, ge2, ge3;
  logic [XW-1:0] r_b;
  logic [1:0]    dig;

  assign r4  = {rem_q[XW-3:0], 2'b00};                       // rem < d <= 2^19: no bits lost
  assign s1  = {1'b0, r4} - {1'b0, div_s_q};
  assign s2  = {1'b0, r4} - {div_s_q, 1'b0};
  assign s3  = {1'b0, r4} - {1'b0, div3_q};
  assign ge1 = !s1[XW];
  assign ge2 = !s2[XW];
  assign ge3 = !s3[XW];
  assign dig = {ge2, ge3 || (ge1 && !ge2)};
  assign r_b = ge3 ? s3[XW-1:0] : ge2 ? s2[XW-1:0] : ge1 ? s1[XW-1:0] : r4;

  // ---- compare-value arithmetic -------------------------------------------------------------------
  logic signed [KWidth-1:0] a8s, b8s, sum_ab, dif_ab, base;
  logic [5:0]               sel;
  logic signed [KWidth-1:0] c_x [3];
  logic [CntWidth-1:0]      c_ph [3];
  logic [3*CntWidth-1:0]    c_new;
  logic [CntWidth-1:0]      c_lo, c_hi, c_mid;
  logic [3*CntWidth-1:0]    lmh_new, lmh_d, lmh_q;     // {hi, mid, lo} of the compare values

  assign a8s    = KWidth'(prod_q[CntWidth+15:8]);            // (T1 * P) >> 8, product of step 28
  assign b8s    = KWidth'(b8_q);
  assign sum_ab = KWidth'($signed(sum_q));
  assign dif_ab = KWidth'($signed(dif_q));
  assign base   = KWidth'({p_q, 8'd0}) + KWidth'(9'd256);   // (P + 1) << 8

  // AVR495 Table 4-3 per phase: 0: +(A+B)  1: -(A+B)  2: +(A-B)  3: -(A-B), A = T1 P, B = T2 P
  svpwm_sector_sel u_sel (          // generated from the model's SECTOR_SEL
    .sector_i (sector_q),
    .sel_o    (sel)
  );

  for (genvar ph = 0; ph < 3; ph++) begin : gen_cmp
    logic signed [KWidth-1:0] k_ph;
    assign k_ph     = sel[2*ph+1] ? dif_ab : sum_ab;         // codes 2, 3: A - B; 0, 1: A + B
    assign c_x[ph]  = (sel[2*ph] ? base - k_ph : base + k_ph) >>> (KFrac + 1);   // odd codes: minus
    assign c_new[ph*CntWidth +: CntWidth] = c_x[ph][CntWidth-1:0];
    assign c_ph[ph] = c_q[ph*CntWidth +: CntWidth];
  end
  assign c_d    = (st_q == 6'd30) ? c_new : c_q;
  // smallest, largest and middle compare value without comparators: per Table 4-3 the phase with code 1
  // (-(A+B)) is the smallest, code 0 (+(A+B)) the largest, codes 2/3 (+-(A-B)) the middle one, since
  // A, B >= 0 (floor keeps the order); registered with the values at step 30
  always_comb begin
    lmh_new = {c_new[CntWidth-1:0], c_new[CntWidth-1:0], c_new[CntWidth-1:0]};
    for (int ph = 0; ph < 3; ph++) begin
      unique case (sel[2*ph +: 2])
        2'd0:    lmh_new[2*CntWidth +: CntWidth] = c_new[ph*CntWidth +: CntWidth];   // hi
        2'd1:    lmh_new[0 +: CntWidth]          = c_new[ph*CntWidth +: CntWidth];   // lo
        default: lmh_new[CntWidth +: CntWidth]   = c_new[ph*CntWidth +: CntWidth];   // mid
      endcase
    end
  end
  assign lmh_d = (st_q == 6'd30) ? lmh_new : lmh_q;
  assign c_lo  = lmh_q[0 +: CntWidth];
  assign c_mid = lmh_q[CntWidth +: CntWidth];
  assign c_hi  = lmh_q[2*CntWidth +: CntWidth];

  logic unused_cx;
  assign unused_cx = ^{c_x[0][KWidth-1:CntWidth], c_x[1][KWidth-1:CntWidth], c_x[2][KWidth-1:CntWidth]};
  // c_x is in [0, P] (see model bound test)

  // ---- sequence ----------------------------------------------------------------------------------
  logic [15:0]   theta6_lo;
  logic [2:0]    theta6_hi;
  logic [15:0]   a16_in;
  logic [15:0]   u16_in;
  logic [24:0]   vf_sum;
  logic [25:0]   vf_t;
  logic [XW-1:0] tsum, tlo, one_minus_q, t1_cl, t2_cl, t1_fin, t2_fin;

  always_comb begin
    {theta6_hi, theta6_lo} = {theta_i, 2'b00} + {1'b0, theta_i, 1'b0};   // 6 theta = sector.a16
    a16_in = (mode_i == ModePolar || mode_i == ModeDq) ? theta6_lo : angle_i;
    u16_in = a16_in[15] ? {1'b0, a16_in[14:0]} : 16'h8000 - a16_in;          // <= 0x8000
    vf_t   = {9'd0, boost_q, 1'b1} + {1'b0, prod_q[31:7]};   // boost + round(p >> 8), one chain
    vf_sum = vf_t[25:1];
    tsum   = t1_q + t2_q;
    tlo    = (t1_q <= t2_q) ? t1_q : t2_q;
    one_minus_q = DOne - XW'(quo_q);
    t1_cl  = !sat_q ? t1_q : first_q ? XW'(quo_q) : one_minus_q;
    t2_cl  = !sat_q ? t2_q : first_q ? one_minus_q : XW'(quo_q);
    t1_fin = (t1_cl[XW-1:16] != '0) ? XW'(16'hFFFF) : t1_cl;    // 16-bit multiplier operand
    t2_fin = (t2_cl[XW-1:16] != '0) ? XW'(16'hFFFF) : t2_cl;
  end

  always_comb begin
    st_d         = st_q;
    mode_d       = mode_q;
    sec0_d       = sec0_q;
    swq_d        = swq_q;
    sector_d     = sector_q;
    dpwm_d       = dpwm_q;
    a16_d        = a16_q;
    u16_d        = u16_q;
    m_d          = m_q;
    fa_d         = fa_q;
    boost_d      = boost_q;
    slope_d      = slope_q;
    mmax_d       = mmax_q;
    v1_d         = v1_q;
    v2_d         = v2_q;
    p_d          = p_q;
    r0_d         = r0_q;
    h_d          = h_q;
    g_d          = g_q;
    sb_d         = sb_q;
    sa_d         = sa_q;
    ct_d         = ct_q;
    c60_d        = c60_q;
    x_d          = x_q;
    y_d          = y_q;
    z_d          = z_q;
    t1_d         = t1_q;
    t2_d         = t2_q;
    div_s_d      = div_s_q;
    div3_d       = div3_q;
    rem_d        = rem_q;
    quo_d        = quo_q;
    sat_d        = sat_q;
    first_d      = first_q;
    err_d        = err_q;
    b8_d         = b8_q;
    sum_d        = sum_q;
    dif_d        = dif_q;
    sh_d         = sh_q;
    cmp_d        = cmp_q;
    sector_out_d = sector_out_q;
    sat_out_d    = sat_out_q;
    err_out_d    = err_out_q;
    done_d       = 1'b0;
    if (idle_q) begin                   // idle: the input registers follow the inputs, so the start clock
      mode_d  = mode_i;                 // takes them without start_i driving ~200 enables
      sec0_d  = (mode_i == ModePolar || mode_i == ModeDq) ? theta6_hi : sector_i;
      a16_d   = a16_in;
      u16_d   = u16_in;                 // |theta' - 30 deg|
      m_d     = m_i;
      fa_d    = fabs_i;
      boost_d = vf_boost_i;
      slope_d = vf_slope_i;
      mmax_d  = vf_mmax_i;
      v1_d    = v1_i;
      v2_d    = v2_i;
      dpwm_d  = dpwm_i;
      p_d     = period_i;
    end
    unique case (st_q)
      6'd0: ;                                                   // idle: inputs taken above
      6'd2:  r0_d = rom_data;                                   // R[j]
      6'd3: begin                                               // AB: X, Y, Z from sqrt3/2 v_alpha
        if (ab) begin
          x_d = XW'({{(XW-18){v2_q[15]}}, v2_q, 2'b00});        // v_beta in dwell units
          y_d = add_rv(XW'({{(XW-17){v2_q[15]}}, v2_q, 1'b0}), pv_h, pv_b, v1_q[15]);
          z_d = add_rv(XW'({{(XW-17){v2_q[15]}}, v2_q, 1'b0}), pv_h, pv_b, !v1_q[15]);
        end
      end
      6'd4: begin
        h_d  = add_ri(r0_q, pi_h, pi_b, 1'b0);                                    // sin(u)
        r0_d = rom_data;                                        // R[256-j]
      end
      6'd5: if (mode_q == ModeVf)                               // V/f law: m = min(m_max, boost + |f| slope)
              m_d = (vf_sum > 25'(mmax_q)) ? mmax_q : vf_sum[15:0];
      6'd6: begin
        g_d  = add_ri(r0_q, pi_h, pi_b, 1'b1);                                    // sin(60 - u)
        r0_d = rom_data;                                        // R[i]
      end
      6'd7: begin                                               // cos theta', cos(60 - theta')
        ct_d  = (a16_q < 16'h8000) ? (({1'b0, g_q} + {1'b0, h_q} > 17'hFFFF) ? 16'hFFFF : g_q + h_q) : g_q;
        c60_d = (a16_q < 16'h8000) ? g_q : (({1'b0, g_q} + {1'b0, h_q} > 17'hFFFF) ? 16'hFFFF : g_q + h_q);
      end
      6'd8: begin
        sb_d = add_ri(r0_q, pi_h, pi_b, 1'b0);                                    // sin(theta')
        r0_d = rom_data;                                        // R[256-i]
      end
      6'd9:  if (dq) x_d = add_rv('0, pv_h, pv_b, v2_q[15]);               // v_q cos theta'
      6'd10: sa_d = add_ri(r0_q, pi_h, pi_b, 1'b1);                               // sin(60 - theta')
      6'd11: begin
        if (dq) z_d = add_rv('0, pv_h, pv_b, v2_q[15]);                    // v_q cos(60 - theta')
        else    t2_d = XW'(p_m);                                // T2 = m sin(theta')
      end
      6'd12: begin
        if (dq) x_d = add_rv(x_q, pv_h, pv_b, v1_q[15]);              // + v_d sin theta'
        else    t1_d = XW'(p_m);                                // T1 = m sin(60 - theta')
      end
      6'd13: if (dq) z_d = add_rv(z_q, pv_h, pv_b, !v1_q[15]);         // - v_d sin(60 - theta')
      6'd14: if (dq) y_d = x_q - z_q;                           // Y = X - Z
      6'd15: begin                                              // sector index; |X|, |Y|, |Z|
        err_d = !(polar_like || ab || dq);
        if (ab || dq) begin
          swq_d    = sw;
          x_d      = abs_xw(x_q);
          y_d      = abs_xw(y_q);
          z_d      = abs_xw(z_q);
        end else if (polar_like) begin
          sector_d = sec0_q;
        end else begin
          sector_d = '0;
          t1_d     = '0;
          t2_d     = '0;
        end
      end
      6'd16: begin                                              // sector, dwell times (AB, DQ)
        if (ab || dq) begin
          sector_d = sw_sum;
          t1_d = pick_q(sw1, x_q, y_q, z_q);
          t2_d = pick_q(swq_q, x_q, y_q, z_q);
        end
      end
      6'd17: begin                                              // hexagon clamp: q = min * 2^16 / sum
        div_s_d = tsum;
        div3_d  = '1;                                           // first digit <= 2 (rem <= d / 2): no 3d
        rem_d   = tlo;
        sat_d   = (tsum[XW-1:17] != '0) || (tsum[16] && tsum[15:0] != '0);   // T1 + T2 > 1, no carry chain
        first_d = t1_q <= t2_q;
        quo_d   = '0;
      end
      6'd18, 6'd19, 6'd20, 6'd21, 6'd22, 6'd23, 6'd24, 6'd25: begin
        rem_d = r_b;
        quo_d = {quo_q[13:0], dig};
        if (st_q == 6'd18) div3_d = div_s_q + {div_s_q[XW-2:0], 1'b0};   // 3 (T1 + T2) from step 19 on
      end
      6'd26: begin                                              // clamped, capped at 1 - 2^-16
        t1_d = t1_fin;
        t2_d = t2_fin;
      end
      6'd28: b8_d = prod_q[CntWidth+15:8];                      // (T2 * P) >> 8
      6'd29: begin                                              // A + B, A - B
        sum_d = (CntWidth+10)'(a8s + b8s);
        dif_d = (CntWidth+10)'(a8s - b8s);
      end
      6'd30: ;                                                  // compare values (above)
      6'd31: begin                                              // zero-vector placement
        unique case (dpwm_q)
          2'd1:    sh_d = $signed({2'b00, p_q}) - $signed({2'b00, c_hi});
          2'd2:    sh_d = -$signed({2'b00, c_lo});
          2'd3:    sh_d = ({c_mid, 1'b0} > {1'b0, p_q})     // middle phase below average: the highest
                          ? -$signed({2'b00, c_lo})        // phase has the largest |reference|: DPWMMAX
                          : $signed({2'b00, p_q}) - $signed({2'b00, c_hi});
          default: sh_d = '0;
        endcase
      end
      6'd32: ;
      6'd33: begin                                              // all results change with done_o
        for (int ph = 0; ph < 3; ph++)
          cmp_d[ph*CntWidth +: CntWidth] = CntWidth'($signed({2'b00, c_ph[ph]}) + sh_q);
        sector_out_d = sector_q;
        sat_out_d    = sat_q;
        err_out_d    = err_q;
        done_d       = 1'b1;
      end
      default: ;
    endcase
    if (st_q == 6'd0) begin
      if (start_i) st_d = 6'd1;
    end else begin
      st_d = (st_q == 6'(LastSt)) ? 6'd0 : st_q + 6'd1;
    end
    if (abort_i) begin                                          // back to idle, the results hold
      st_d         = 6'd0;
      done_d       = 1'b0;
      cmp_d        = cmp_q;
      sector_out_d = sector_out_q;
      sat_out_d    = sat_out_q;
      err_out_d    = err_out_q;
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      st_q         <= '0;
      idle_q       <= 1'b1;
      mode_q       <= '0;
      sec0_q       <= '0;
      swq_q        <= '0;
      sector_q     <= '0;
      dpwm_q       <= '0;
      a16_q        <= '0;
      u16_q        <= '0;
      m_q          <= '0;
      fa_q         <= '0;
      boost_q      <= '0;
      slope_q      <= '0;
      mmax_q       <= '0;
      v1_q         <= '0;
      v2_q         <= '0;
      p_q          <= '0;
      r0_q         <= '0;
      h_q          <= '0;
      g_q          <= '0;
      sb_q         <= '0;
      sa_q         <= '0;
      ct_q         <= '0;
      c60_q        <= '0;
      x_q          <= '0;
      y_q          <= '0;
      z_q          <= '0;
      t1_q         <= '0;
      t2_q         <= '0;
      div_s_q      <= '0;
      div3_q       <= '0;
      rem_q        <= '0;
      quo_q        <= '0;
      sat_q        <= 1'b0;
      first_q      <= 1'b0;
      err_q        <= 1'b0;
      b8_q         <= '0;
      sum_q        <= '0;
      dif_q        <= '0;
      sh_q         <= '0;
      lmh_q        <= '0;
      c_q          <= '0;
      cmp_q        <= '0;
      sector_out_q <= '0;
      sat_out_q    <= 1'b0;
      err_out_q    <= 1'b0;
      done_q       <= 1'b0;
    end else begin
      st_q         <= st_d;
      idle_q       <= idle_d;
      mode_q       <= mode_d;
      sec0_q       <= sec0_d;
      swq_q        <= swq_d;
      sector_q     <= sector_d;
      dpwm_q       <= dpwm_d;
      a16_q        <= a16_d;
      u16_q        <= u16_d;
      m_q          <= m_d;
      fa_q         <= fa_d;
      boost_q      <= boost_d;
      slope_q      <= slope_d;
      mmax_q       <= mmax_d;
      v1_q         <= v1_d;
      v2_q         <= v2_d;
      p_q          <= p_d;
      r0_q         <= r0_d;
      h_q          <= h_d;
      g_q          <= g_d;
      sb_q         <= sb_d;
      sa_q         <= sa_d;
      ct_q         <= ct_d;
      c60_q        <= c60_d;
      x_q          <= x_d;
      y_q          <= y_d;
      z_q          <= z_d;
      t1_q         <= t1_d;
      t2_q         <= t2_d;
      div_s_q      <= div_s_d;
      div3_q       <= div3_d;
      rem_q        <= rem_d;
      quo_q        <= quo_d;
      sat_q        <= sat_d;
      first_q      <= first_d;
      err_q        <= err_d;
      b8_q         <= b8_d;
      sum_q        <= sum_d;
      dif_q        <= dif_d;
      sh_q         <= sh_d;
      lmh_q        <= lmh_d;
      c_q          <= c_d;
      cmp_q        <= cmp_d;
      sector_out_q <= sector_out_d;
      sat_out_q    <= sat_out_d;
      err_out_q    <= err_out_d;
      done_q       <= done_d;
    end
  end

  // the shared multiplier's product register has no reset, so that synthesis can place it in the DSP's
  // output register (SB_MAC16); it is written every clock and read only in the step after its product
  always_ff @(posedge clk_i) begin
    prod_q <= prod_d;
  end

  assign idle_d   = st_d == 6'd0;
  assign busy_o   = st_q != 6'd0;
  assign done_o   = done_q;
  assign sector_o = sector_out_q;
  assign cmp_o    = cmp_q;
  assign sat_o    = sat_out_q;
  assign err_o    = err_out_q;

endmodule

`default_nettype wire
