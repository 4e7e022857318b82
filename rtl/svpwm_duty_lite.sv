// SPDX-License-Identifier: Apache-2.0
// svpwm_duty_lite: small serial duty calculator of the compact core (FREQ mode only, continuous SVPWM,
// no DSP): sector + in-sector angle + magnitude m -> three snapped compare values, bit-exact with
// model/svpwm_model/fixed.py: snap_min_pulse(dwell_compare(sector, hex_clamp(duties(a16, m)), P), P, thr).
//   sines   sb = sin(theta'), sa = sin(60 deg - theta') by linear interpolation of the 0..60 deg sine_rom
//           (AVR495 sec. 4.2/6), duties T1 = m sa, T2 = m sb (Minas eq. (4)), each (m s + 2^14) >> 15
//   clamp   T1 + T2 > 1: q = floor(min(T1, T2) 2^16 / (T1 + T2)), the other 1 - q (Minas eq. (5)), cap 0xFFFF
//   compare A = (T1 P) >> 8, B = (T2 P) >> 8, C = ((P + 1) 2^8 +- A +- B) >> 9 per AVR495 Table 4-3
//   snap    minimum-pulse rule on each C with thr = dead time + minimum pulse (as rtl/svpwm_minpulse.sv)
// One 26-bit adder does everything, one operation per clock: a radix-2 right-shift
// multiplier (multiplicand pre-shifted so the accumulator ends on the wanted bits, rounding constants
// preloaded), a non-restoring divider (2 rem -+ D), sums, and the compare values; one combinational snap.
// Parameters: CntWidth - period / compare width (8..16); DtWidth - thr_i is DtWidth + 1 bits.
// Latency: Latency = 113 clocks from start_i to done_o, fixed (independent of the data); outputs hold until
// the next done_o (also across abort_i, which returns to idle without done_o); the done cycle is idle, so
// back-to-back starts work. Restrictions: period_i >= 2 * thr_i (svpwm_core clamps); start_i is ignored
// while busy_o; sector_i 0..5.
`default_nettype none

module svpwm_duty_lite #(
  parameter int CntWidth = 16,   // period / compare width, 8..16
  parameter int DtWidth  = 10    // dead-time width; thr_i has DtWidth + 1 bits
) (
  input  logic                  clk_i,      // core clock
  input  logic                  rst_ni,     // asynchronous reset, active low
  input  logic                  start_i,    // sample the inputs below and start (ignored while busy_o)
  input  logic                  abort_i,    // back to idle at once, no done_o, outputs hold
  input  logic [2:0]            sector_i,   // 0..5
  input  logic [15:0]           angle_i,    // a16: in-sector angle theta' / 60 deg, UQ0.16
  input  logic [15:0]           m_i,        // UQ1.15, any value (beyond the hexagon: clamped, sat_o)
  input  logic [CntWidth-1:0]   period_i,   // half period P
  input  logic [DtWidth:0]      thr_i,      // dead time + minimum pulse
  output logic                  busy_o,     // a computation is running
  output logic                  done_o,     // one-clock pulse: the outputs below are new
  output logic [2:0]            sector_o,   // sector of the result
  output logic [3*CntWidth-1:0] cmp_o,      // {C_c, C_b, C_a}, snapped, each in [0, P]
  output logic                  sat_o       // the reference was clamped to the hexagon
);

  localparam int Latency = 113;               // clocks start_i -> done_o (model LITE_DUTY_LATENCY)
  localparam int W       = 26;                // adder / accumulator width (R 2^8 + 128 interpolation preload)
  localparam int TW      = DtWidth + 1;       // thr width
  localparam logic [6:0] LastSt = 7'(Latency - 1);

  if (CntWidth < 8 || CntWidth > 16) begin : gen_bad_width
    initial $fatal(1, "svpwm_duty_lite: CntWidth must be 8..16, got %0d", CntWidth);
  end
  if (TW > CntWidth) begin : gen_bad_dt
    initial $fatal(1, "svpwm_duty_lite: need DtWidth + 1 <= CntWidth, got %0d / %0d", DtWidth, CntWidth);
  end

  // ---- schedule (st_q = step; the ROM answers one step after its address) -----------------------
  //   0 (idle) address R[i+1] from angle_i, so that the start clock already reads the ROM
  //   1..2     R[i+1], R[i]: d = R[i+1] - R[i]; a = R[i] 2^8 + 128
  //   3..10    8 multiply steps d * fr                       -> a = sb
  //   11..12   R[255-i], R[256-i]: d = -(R[256-i] - R[255-i]); h = sb; a = R[256-i] 2^8 + 127
  //   13..20   8 multiply steps (-d2) * fr                   -> a = sa
  //   21       l = sa, a = 2^15
  //   22..37   16 multiply steps (2m) * sa                   -> a = T1 = (m sa + 2^14) >> 15
  //   38       l = sb, h = T1, a = 2^15
  //   39..54   16 multiply steps (2m) * sb                   -> a = T2
  //   55       first = T1 <= T2 (sign of T2 - T1)
  //   56       s = T1 + T2, sat = s > 2^16; h = D = sat ? s : 2^16; a = min; mx = cap(max)
  //   57..72   16 non-restoring divide steps min 2^16 / D    -> l = q (= min when not saturated)
  //   73       mx = cap(2^16 - q) if sat (the larger dwell time); a = 0
  //   74..89   16 multiply steps (P 2^8) * q                 -> a = floor(q P / 2^8)
  //   90       h = a, l = mx, a = 0
  //   91..106  16 multiply steps (P 2^8) * mx                -> a = floor(mx P / 2^8)
  //   107      h = Dd = (mx P >> 8) - (q P >> 8)   (>= 0)
  //   108      a = S  = (mx P >> 8) + (q P >> 8)
  //   109..111 phase a, b, c: C = (base +- S or +- Dd) >> 9 into l (a and h swap so that a holds the K of
  //            the phase); 110..112 snap the C of the step before; results with done_o after 112
  localparam logic [6:0] StInterp0 = 7'd3,  StInterp1 = 7'd13, StDuty0 = 7'd22, StDuty1 = 7'd39;
  localparam logic [6:0] StCmpDiff = 7'd55, StSum = 7'd56, StDiv = 7'd57, StTmax = 7'd73;
  localparam logic [6:0] StProd0 = 7'd74, StProd1 = 7'd91, StDd = 7'd107, StS = 7'd108, StC = 7'd109;

  // ---- state -------------------------------------------------------------------------------------
  logic [6:0]            st_d, st_q;
  logic                  idle_d, idle_q;
  logic [2:0]            sec_d, sec_q, sector_out_d, sector_out_q;
  logic [CntWidth-1:0]   p_d, p_q;
  logic [TW-1:0]         thr_d, thr_q;
  logic [7:0]            idx_d, idx_q;          // ROM index of theta'
  logic [15:0]           m_d, m_q;              // m, later the larger dwell time, later a result
  logic [15:0]           l_d, l_q;              // multiplier operand (shifts right) / quotient (shifts left)
  logic [9:0]            d_d, d_q;              // signed ROM difference (interpolation multiplicand)
  logic [W-1:0]          a_d, a_q;              // accumulator / remainder
  logic [W-1:0]          h_d, h_q;              // held operand
  logic                  first_d, first_q, sat_d, sat_q, sat_out_d, sat_out_q, done_d, done_q;
  logic [3*CntWidth-1:0] cmp_d, cmp_q;

  // ---- sine ROM ----------------------------------------------------------------------------------
  logic [8:0]  rom_addr;
  logic [15:0] rom_data;

  sine_rom u_rom (
    .clk_i  (clk_i),
    .addr_i (rom_addr),
    .data_o (rom_data)
  );

  // idle, steps 1, 10, 11: R[i+1], R[i], R[255-i], R[256-i]; 255 - i = ~i, so one incrementer:
  // st_q[3] picks ~i (steps 10, 11), 1 is added when idle and in step 11
  logic [7:0] rom_i;
  assign rom_i    = idle_q ? angle_i[15:8] : idx_q ^ {8{st_q[3]}};
  assign rom_addr = {1'b0, rom_i} + {8'd0, idle_q | (st_q[0] & st_q[3])};

  // ---- step decode ---------------------------------------------------------------------------------
  // step-class masks indexed by st_q (a lookup, no comparators)
  function automatic logic [127:0] steps(input logic [6:0] first, input int n);
    steps = '0;
    for (int k = int'(first); k < int'(first) + n; k++) steps[k] = 1'b1;
  endfunction
  localparam logic [127:0] MaskInterp = steps(StInterp0, 8) | steps(StInterp1, 8);
  localparam logic [127:0] MaskDuty   = steps(StDuty0, 16) | steps(StDuty1, 16);
  localparam logic [127:0] MaskMul    = MaskInterp | MaskDuty | steps(StProd0, 16) | steps(StProd1, 16);
  localparam logic [127:0] MaskDiv    = steps(StDiv, 16);
  localparam logic [127:0] MaskC      = steps(StC, 3);

  logic ph_interp, ph_duty, ph_mul, ph_div, ph_c;
  assign ph_interp = MaskInterp[st_q];
  assign ph_duty   = MaskDuty[st_q];
  assign ph_mul    = MaskMul[st_q];
  assign ph_div    = MaskDiv[st_q];
  assign ph_c      = MaskC[st_q];

  // ---- compare-value selection: AVR495 Table 4-3 ------------------------------------------------
  // per phase: 0: +(A+B)  1: -(A+B)  2: +(A-B)  3: -(A-B), A = T1 P, B = T2 P
  function automatic logic [5:0] sector_sel(input logic [2:0] s);
    unique case (s)
      3'd0:    sector_sel = {2'd0, 2'd2, 2'd1};   // sector 1: a -da-db, b da-db, c da+db
      3'd1:    sector_sel = {2'd0, 2'd1, 2'd3};   // sector 2: a -da+db, b -da-db, c da+db
      3'd2:    sector_sel = {2'd2, 2'd1, 2'd0};   // sector 3: a da+db, b -da-db, c da-db
      3'd3:    sector_sel = {2'd1, 2'd3, 2'd0};   // sector 4: a da+db, b -da+db, c -da-db
      3'd4:    sector_sel = {2'd1, 2'd0, 2'd2};   // sector 5: a da-db, b da+db, c -da-db
      default: sector_sel = {2'd3, 2'd0, 2'd1};   // sector 6: a -da-db, b da+db, c -da+db
    endcase
  endfunction

  logic [5:0] sel;
  logic [1:0] code;          // code of the phase of this step (110: a, 111: b, 112: c)
  logic       c_neg;         // this phase adds -K (K = S for codes 0, 1; Dd for 2, 3, in a_q then)
  assign sel   = sector_sel(sec_q);
  assign code  = (st_q == StC) ? sel[1:0] : (st_q == StC + 7'd1) ? sel[3:2] : sel[5:4];
  // A - B = -Dd when T1 is the smaller dwell time (first), +Dd otherwise
  assign c_neg = code[1] ? (code[0] ^ first_q) : code[0];

  // ---- the adder: r = opa + (opb ^ inv) + cin ------------------------------------------------------
  logic [W-1:0] opa, opb, xsel, base, r;
  logic [W:0]   t;
  logic         inv, cin;

  assign base = W'({{1'b0, p_q} + (CntWidth+1)'(1), 8'd0});   // (P + 1) 2^8

  always_comb begin
    if (ph_interp)    xsel = W'({{(W-10){d_q[9]}}, d_q});      // +-ROM difference
    else if (ph_duty) xsel = W'({m_q, 1'b0});                   // 2m: product ends at >> 15
    else              xsel = W'({p_q, 8'd0});                   // P 2^8: product ends at >> 8
  end

  always_comb begin
    opa = a_q;                                        // multiply step, T2 - T1, T1 + T2, Dd
    opb = h_q;
    inv = 1'b0;
    cin = 1'b0;
    if (ph_mul) begin
      opb = l_q[0] ? xsel : '0;
    end else if (ph_div) begin                        // non-restoring: 2 rem -+ D by the sign of rem
      opa = {a_q[W-2:0], 1'b0};
      inv = !a_q[W-1];
      cin = !a_q[W-1];
    end else if (st_q == StS) begin                   // 2 (mx P >> 8) - Dd
      opa = {a_q[W-2:0], 1'b0};
      inv = 1'b1;
      cin = 1'b1;
    end else if (st_q == StCmpDiff || st_q == StDd) begin
      inv = 1'b1;
      cin = 1'b1;
    end else if (st_q == StTmax) begin                // -q
      opa = '0;
      opb = W'(l_q);
      inv = 1'b1;
      cin = 1'b1;
    end else if (ph_c) begin                          // K + base, or K + ~base = K - base - 1
      opb = base;
      inv = c_neg;
    end
  end

  // one carry chain: the extra LSB column turns cin into the carry-in (its sum bit is discarded)
  logic unused_t0;
  assign t         = {opa, 1'b1} + {opb ^ {W{inv}}, cin};
  assign r         = t[W:1];
  assign unused_t0 = t[0];

  // ---- derived values ------------------------------------------------------------------------------
  logic         ge, s_gt;
  logic [15:0]  mx_cap, tmax;
  logic [W-1:0] mx;
  assign ge     = !r[W-1];                                       // 2 rem - D >= 0; T2 - T1 >= 0
  assign s_gt   = (r[W-1:17] != '0) || (r[16] && (r[15:0] != '0));   // T1 + T2 > 2^16
  assign mx     = first_q ? a_q : h_q;                           // the larger dwell time
  assign mx_cap = (mx[W-1:16] != '0) ? 16'hFFFF : mx[15:0];
  assign tmax   = r[16] ? r[15:0] : 16'hFFFF;                    // 2^16 - q, q = 0 capped

  // compare value of this phase: (base +- K) >> 9 (for -K: base - K = ~(K - base - 1))
  logic [CntWidth-1:0] c_val, c_snap;
  assign c_val = c_neg ? ~r[CntWidth+8:9] : r[CntWidth+8:9];

  // ---- minimum-pulse snap (fixed.snap_min_pulse): c < thr -> 0 or thr; P - c < ceil(thr/2) -> P or
  // P - ceil(thr/2), whichever is nearer. Requires P >= 2 thr, c <= P.
  localparam int SW = CntWidth + 2;
  logic [SW-1:0] s_c, s_thr, s_hthr, s_e, s_p;
  assign s_c    = SW'(l_q[CntWidth-1:0]);            // the compare value of the previous step
  assign s_p    = SW'(p_q);
  assign s_thr  = SW'(thr_q);
  assign s_hthr = (s_thr + SW'(1)) >> 1;
  assign s_e    = s_p - s_c;
  always_comb begin
    c_snap = l_q[CntWidth-1:0];
    if (s_c < s_thr) begin
      c_snap = ({s_c[SW-2:0], 1'b0} < s_thr) ? '0 : CntWidth'(thr_q);
    end else if (s_e < s_hthr) begin
      c_snap = ({s_e[SW-2:0], 1'b0} < s_hthr) ? p_q : CntWidth'(s_p - s_hthr);
    end
  end

  // ---- sequence ----------------------------------------------------------------------------------
  always_comb begin
    st_d         = st_q;
    sec_d        = sec_q;
    p_d          = p_q;
    thr_d        = thr_q;
    idx_d        = idx_q;
    m_d          = m_q;
    l_d          = l_q;
    d_d          = d_q;
    a_d          = a_q;
    h_d          = h_q;
    first_d      = first_q;
    sat_d        = sat_q;
    cmp_d        = cmp_q;
    sector_out_d = sector_out_q;
    sat_out_d    = sat_out_q;
    done_d       = 1'b0;
    if (idle_q) begin                   // idle: the input registers follow the inputs
      sec_d = sector_i;
      p_d   = period_i;
      thr_d = thr_i;
      idx_d = angle_i[15:8];
      m_d   = m_i;
      l_d   = {angle_i[7:0], angle_i[7:0]};   // fr twice: one copy per interpolation
    end
    if (ph_mul) begin                   // a = (a + y x) >> 1, y = next multiplier bit
      a_d = {1'b0, r[W-1:1]};
      l_d = {1'b0, l_q[15:1]};
    end
    if (ph_div) begin                   // non-restoring: rem = 2 rem -+ D; quotient bit = rem >= 0
      a_d = r;
      l_d = {l_q[14:0], ge};
    end
    unique case (st_q)
      7'd1:  d_d = rom_data[9:0];                               // R[i+1]
      7'd2: begin
        d_d = d_q - rom_data[9:0];                              // R[i+1] - R[i]
        a_d = W'({rom_data, 8'h80});
      end
      7'd11: begin
        d_d = rom_data[9:0];                                    // R[255-i]
        h_d = a_q;                                              // sb
      end
      7'd12: begin
        d_d = d_q - rom_data[9:0];                              // -(R[256-i] - R[255-i])
        a_d = W'({rom_data, 8'h7F});                            // r2 - ((z + 128) >> 8) = (256 r2 + 127 - z) >> 8
      end
      7'd21: begin
        l_d = a_q[15:0];                                        // sa
        a_d = W'(32'h8000);
      end
      7'd38: begin
        l_d = h_q[15:0];                                        // sb
        h_d = a_q;                                              // T1
        a_d = W'(32'h8000);
      end
      StCmpDiff: first_d = ge;                                  // T1 <= T2
      StSum: begin
        sat_d = s_gt;
        h_d   = s_gt ? r : W'(32'h1_0000);                      // divisor
        a_d   = first_q ? h_q : a_q;                            // min(T1, T2)
        m_d   = mx_cap;
      end
      StTmax: begin
        if (sat_q) m_d = tmax;
        a_d = '0;
      end
      7'd90: begin
        h_d = a_q;                                              // (q P) >> 8
        l_d = m_q;
        a_d = '0;
      end
      StDd: h_d = r;
      StS: begin                                                // a = K of phase a, h = the other
        if (sel[1]) begin
          a_d = h_q;
          h_d = r;
        end else begin
          a_d = r;
        end
      end
      7'd109: begin
        l_d = 16'(c_val);                                       // C_a
        if (sel[1] != sel[3]) begin                             // phase b needs the other K
          a_d = h_q;
          h_d = a_q;
        end
      end
      7'd110: begin
        m_d = 16'(c_snap);                                      // C_a snapped
        l_d = 16'(c_val);                                       // C_b
        if (sel[3] != sel[5]) begin
          a_d = h_q;
          h_d = a_q;
        end
      end
      7'd111: begin
        h_d = W'(c_snap);                                       // C_b snapped
        l_d = 16'(c_val);                                       // C_c
      end
      7'd112: begin
        cmp_d        = {c_snap, h_q[CntWidth-1:0], m_q[CntWidth-1:0]};
        sector_out_d = sec_q;
        sat_out_d    = sat_q;
        done_d       = 1'b1;
      end
      default: ;
    endcase
    if (st_q == 7'd0) begin
      if (start_i) st_d = 7'd1;
    end else begin
      st_d = (st_q == LastSt) ? 7'd0 : st_q + 7'd1;
    end
    if (abort_i) begin                  // back to idle, the results hold
      st_d         = 7'd0;
      done_d       = 1'b0;
      cmp_d        = cmp_q;
      sector_out_d = sector_out_q;
      sat_out_d    = sat_out_q;
    end
  end

  assign idle_d = st_d == 7'd0;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      st_q         <= '0;
      idle_q       <= 1'b1;
      sec_q        <= '0;
      p_q          <= '0;
      thr_q        <= '0;
      idx_q        <= '0;
      m_q          <= '0;
      l_q          <= '0;
      d_q          <= '0;
      a_q          <= '0;
      h_q          <= '0;
      first_q      <= 1'b0;
      sat_q        <= 1'b0;
      cmp_q        <= '0;
      sector_out_q <= '0;
      sat_out_q    <= 1'b0;
      done_q       <= 1'b0;
    end else begin
      st_q         <= st_d;
      idle_q       <= idle_d;
      sec_q        <= sec_d;
      p_q          <= p_d;
      thr_q        <= thr_d;
      idx_q        <= idx_d;
      m_q          <= m_d;
      l_q          <= l_d;
      d_q          <= d_d;
      a_q          <= a_d;
      h_q          <= h_d;
      first_q      <= first_d;
      sat_q        <= sat_d;
      cmp_q        <= cmp_d;
      sector_out_q <= sector_out_d;
      sat_out_q    <= sat_out_d;
      done_q       <= done_d;
    end
  end

  assign busy_o   = st_q != 7'd0;
  assign done_o   = done_q;
  assign sector_o = sector_out_q;
  assign cmp_o    = cmp_q;
  assign sat_o    = sat_out_q;

endmodule

`default_nettype wire
