// SPDX-License-Identifier: Apache-2.0
// svpwm_calc: the core's one calculator -- a reference in any input mode -> sector, dwell times, hexagon
// clamp (or the six-step overmodulation law), compare values (AVR495 Table 4-3), zero-vector placement,
// dead-time compensation and the minimum-pulse rule; exactly model/svpwm_model/fixed.py:
// snap_min_pulse(modulate(...)) per phase.
// A microcoded accumulator machine (model/svpwm_model/calc_prog.py generates its program and models it clock
// by clock; docs/design.md): one adder ACC <- A + B + cin, a 32-word operand RAM (svpwm_calc_ram), the sine
// ROM, one 16 x 16 multiplier and a microcode ROM (svpwm_ucode) addressed by a step counter. Per clock:
//   A = aen ? (ash ? ACC << 1 : ACC) : 0;  B = (RAM word or AUX) ^ {binv}
//   ACC <- A + B + cin (or held: a compare); RAM[dst] <- ACC; flag[dst] <- sign, Q <- {Q, !sign} (both
//   one clock later, from the registered sign); MA / MB <- sat16(B, ACC or the angle fraction);
//   P <- MA * MB (registered inputs and output: the UP5K's SB_MAC16 with its registers) or, with Dsp = 0,
//   a 16-clock serial shift-add unit.
// Timing (every select from a register): word k holds the own fields of step k, the A selection (aen,
// ash) of step k + 1, the operand selection of step k + 2 (both registered in step k) and the condition
// selection of step k + 3 (registered in step k; its condition bits -- c[cond], sector / snap / DPWM
// read-address bits -- are registered in step k + 1). The sum's sign is registered (sign_q). The
// builder (calc_prog.Builder) waits for what that delays: a flag is a condition four steps after its
// step, a ROM word four steps after its angle, an out step two steps after the sector; the division's
// BinvNsign uses the sign of the step two before (a hold between its steps); step 1 is empty.
// TRANSITIONAL: the tiny build (Features = svpwm_pkg::CfgTiny) still instantiates its own serial datapath
// (rtl/svpwm_duty_lite.sv, latency svpwm_pkg::LiteDutyLatency, FREQ only: mode_i ignored): the engine's tiny
// program (236 clocks, bit-exact in the model) does not fit the iCEstick's HX1K yet (1,685 / 1,280 LC).
// Parameters: Features - the build (svpwm_pkg Feat* bits / Cfg* configurations; model/svpwm_model/config.py):
//             the program of its calculator features (svpwm_ucode); the inputs of features it lacks are not
//             read (theta_i without POLAR / DQ, v1_i / v2_i without AB / DQ, vf_*_i / fabs_i without VF,
//             dpwm_i, om_i, isign_i / hdr_i / hdf_i, carry_i / carry_en_i without DPWM, SIXSTEP, DTC, CARRY), a
//             mode it lacks gives the zero vector and err_o; its Dsp bit: 1 the registered multiplier, 0 the
//             serial unit; CntWidth - period / compare width (8..16); DtWidth - thr_i is DtWidth + 1 bits.
// Latency: svpwm_pkg::core_latency(Features) clocks from start_i to done_o.
// Volt-second carry: carry_i (with carry_en_i) is added to each phase's command before the minimum-pulse
// rule; carry_o is what the rule dropped or widened, limited to +-ceil(thr / 2) (fixed.snap_carry), for the
// core to give back in the next update; carry_o is valid from the second clock after done_o until the next
// computation's out steps.
// Restrictions: sector_i and angle_i are read at start_i only; every other input must hold from start_i
// until done_o (the core's sampled registers do), except fabs_i, period_i, thr_i, hdr_i and hdf_i, which may
// arrive one
// clock after start_i (read from step 1 on: model/tests/test_calc_prog.py); start_i is ignored while
// busy_o; sector_o, cmp_o, sat_o and err_o are the results in the done_o clock only (they change while
// busy_o); period_i >= 2 thr_i.
`default_nettype none

module svpwm_calc #(
  parameter logic [31:0] Features = svpwm_pkg::CfgFull,
  parameter int CntWidth = 16,
  parameter int DtWidth  = 10
) (
  input  logic                  clk_i,        // core clock
  input  logic                  rst_ni,       // asynchronous reset, active low
  input  logic                  start_i,      // start a computation (ignored while busy_o)
  input  logic                  abort_i,      // back to idle, no done_o
  input  logic [2:0]            mode_i,       // input mode (svpwm_core)
  input  logic [2:0]            sector_i,     // phase accumulator: sector 0..5 (FREQ, VF), at start_i
  input  logic [15:0]           angle_i,      // phase accumulator: theta' / 60 deg, UQ0.16, at start_i
  input  logic [15:0]           theta_i,      // electrical angle, 2^16 = 360 deg (POLAR, DQ)
  input  logic [15:0]           m_i,          // magnitude, UQ1.15 (FREQ, POLAR)
  input  logic [15:0]           fabs_i,       // |frequency word| >> (FreqWidth - 17) (VF)
  input  logic signed [15:0]    v1_i,         // v_alpha or v_d, Q2.14 (AB, DQ)
  input  logic signed [15:0]    v2_i,         // v_beta or v_q, Q2.14 (AB, DQ)
  input  logic [15:0]           vf_boost_i,   // V/f: m at zero frequency, UQ1.15
  input  logic [15:0]           vf_slope_i,   // V/f: m LSBs per fabs_i LSB, UQ8.8
  input  logic [15:0]           vf_mmax_i,    // V/f: largest m, UQ1.15
  input  logic [1:0]            dpwm_i,       // 0 SVPWM, 1 DPWMMIN, 2 DPWMMAX, 3 DPWM1 (60 deg)
  input  logic                  om_i,         // 1: six-step overmodulation law (FREQ, VF, POLAR)
  input  logic [CntWidth-1:0]   period_i,     // half carrier period P the compare values are scaled to
  input  logic [DtWidth:0]      thr_i,        // dead time + minimum pulse (minimum-pulse rule)
  input  logic [2:0]            isign_i,      // current signs {c, b, a}, 1 = negative (compensation)
  input  logic [DtWidth-1:0]    hdr_i,        // compensation: C - hdr_i for a positive current (0: off)
  input  logic [DtWidth-1:0]    hdf_i,        // compensation: C + hdf_i for a negative current (0: off)
  input  logic [3*DtWidth+5:0]  carry_i,      // {c, b, a} volt-second carry in, DtWidth + 2 bits signed each
  input  logic                  carry_en_i,   // 1: add carry_i (0: as if it were 0); |carry| <= 2^DtWidth
  output logic                  busy_o,       // a computation is running
  output logic                  done_o,       // one-cycle pulse: the outputs below are new
  output logic [2:0]            sector_o,     // sector of the result
  output logic [3*CntWidth-1:0] cmp_o,        // {C_c, C_b, C_a}, each in [0, P], snapped
  output logic                  sat_o,        // the reference was clamped to the hexagon
  output logic                  err_o,        // invalid mode: zero vector
  output logic [3*DtWidth+5:0]  carry_o       // {c, b, a} carry out: command - snapped, at most +-ceil(thr/2)
);
  localparam int EW = DtWidth + 2;            // carry width (signed): |carry| <= ceil(thr / 2) <= 2^DtWidth
  localparam bit Dsp      = svpwm_pkg::has(Features, svpwm_pkg::FeatDsp);
  localparam bit HasTheta = svpwm_pkg::has_theta(Features);
  localparam bit HasXy    = svpwm_pkg::has_xy(Features);
  localparam bit HasVf    = svpwm_pkg::has(Features, svpwm_pkg::FeatVf);
  localparam bit HasDpwm  = svpwm_pkg::has(Features, svpwm_pkg::FeatDpwm);
  localparam bit HasSix   = svpwm_pkg::has(Features, svpwm_pkg::FeatSixstep);
  localparam bit HasDtc   = svpwm_pkg::has(Features, svpwm_pkg::FeatDtc);
  localparam bit HasCarry = svpwm_pkg::has(Features, svpwm_pkg::FeatCarry);
  // the mode codes built (bit = code, svpwm_pkg::FeatFreq .. FeatDq)
  localparam logic [4:0] ModesBuilt = 5'(Features);

  if (svpwm_pkg::is_tiny(Features)) begin : gen_lite
    svpwm_duty_lite #(.CntWidth(CntWidth), .DtWidth(DtWidth)) u_duty (
      .clk_i    (clk_i),
      .rst_ni   (rst_ni),
      .start_i  (start_i),
      .abort_i  (abort_i),
      .sector_i (sector_i),
      .angle_i  (angle_i),
      .m_i      (m_i),
      .period_i (period_i),
      .thr_i    (thr_i),
      .busy_o   (busy_o),
      .done_o   (done_o),
      .sector_o (sector_o),
      .cmp_o    (cmp_o),
      .sat_o    (sat_o)
    );
    assign err_o = 1'b0;
    assign carry_o = '0;

    logic unused_full;
    assign unused_full = ^{mode_i, theta_i, v1_i, v2_i, vf_boost_i, vf_slope_i, vf_mmax_i, dpwm_i, fabs_i, Dsp,
                           isign_i, hdr_i, hdf_i, om_i, carry_i, carry_en_i};
  end else begin : gen_engine
    localparam int W       = svpwm_pkg::acc_width(CntWidth);
    localparam int Latency = svpwm_pkg::calc_latency(Features);
    // the field values the program uses (a bit per value): only their multiplexer arms, flags and
    // conditions are built (a value outside never reaches the decode: svpwm_pkg::used_*)
    localparam logic [31:0] UsedSrc  = svpwm_pkg::used_src(Features);
    localparam logic [31:0] UsedIsel = svpwm_pkg::used_isel(Features);
    localparam logic [31:0] UsedPsh  = svpwm_pkg::used_psh(Features);
    localparam logic [31:0] UsedRc   = svpwm_pkg::used_rc(Features);
    localparam logic [31:0] UsedFlag = svpwm_pkg::used_flag(Features);
    localparam logic [31:0] UsedSec  = svpwm_pkg::used_sec(Features);
    localparam logic [31:0] UsedPred = svpwm_pkg::used_pred(Features);
    localparam logic [31:0] UsedBinv = svpwm_pkg::used_binv(Features);
    localparam logic [31:0] UsedCin  = svpwm_pkg::used_cin(Features);
    localparam logic [31:0] UsedCond = svpwm_pkg::used_cond(Features);

    // ---- step counter and microcode ------------------------------------------------------------------
    logic [8:0]        pc_d, pc_q;
    logic              busy, busy_d, busy_q;
    logic [svpwm_pkg::UcBits-1:0] word;

    assign busy   = busy_q;                      // == (pc_q != 0), registered
    // == (pc_d != 0), written so that start_i / abort_i pass one LUT only
    assign busy_d = !abort_i && (busy ? (pc_q != 9'(Latency - 1)) : start_i);
    always_comb begin
      pc_d = 9'd0;
      if (abort_i)                        pc_d = 9'd0;
      else if (busy)                      pc_d = (pc_q == 9'(Latency - 1)) ? 9'd0 : pc_q + 9'd1;
      else if (start_i)                   pc_d = 9'd1;
    end

    svpwm_ucode #(.Features(Features)) u_ucode (
      .clk_i  (clk_i),
      .addr_i (pc_d),
      .word_o (word)
    );
    // idle, the ROM reads word 0 (pc_d = 0): the idle word, step 1's operand selection, with no own
    // fields (only in the very first clock after configuration may the ROM register hold anything else;
    // the core cannot start then). The own fields below act only while busy.

    // ---- decode: own fields (acting in this step, only while busy) ------------------------------------
    logic       aen_q, ash_q, hold, we, fset, qsh, ald, mla, mas, mlb, done;
    logic [4:0] dst;
    logic [2:0] pred, rsel;
    logic [1:0] mbs, sec_op, out_op;
    logic [4:0] mop;
    logic [8:0] misc;

    // aen / ash: the A operand of the next step, registered (A only matters while busy: ACC holds
    // otherwise)
    logic aen_d, ash_d;
    assign aen_d = word[svpwm_pkg::UcAen];
    assign ash_d = word[svpwm_pkg::UcAsh];
    assign hold = word[svpwm_pkg::UcHold];
    assign dst  = word[svpwm_pkg::UcDst +: svpwm_pkg::UcDstW];
    assign pred = word[svpwm_pkg::UcPred +: svpwm_pkg::UcPredW];
    assign mop  = svpwm_pkg::uc_mop(word[svpwm_pkg::UcMop +: svpwm_pkg::UcMopW]);
    assign misc = svpwm_pkg::uc_misc(word[svpwm_pkg::UcMisc +: svpwm_pkg::UcMiscW]);
    assign we   = busy && (word[svpwm_pkg::UcWr +: svpwm_pkg::UcWrW] == 2'(svpwm_pkg::WrRam));
    assign fset = busy && (word[svpwm_pkg::UcWr +: svpwm_pkg::UcWrW] == 2'(svpwm_pkg::WrFlag));
    assign {mla, mas, mlb, mbs} = busy ? mop : 5'd0;
    assign {qsh, ald, sec_op, rsel, out_op} = busy ? misc : 9'd0;
    assign done = busy && word[svpwm_pkg::UcDone];

    // next fields: the operand of the step after next (registered here: the operand multiplexers of the
    // next step select from registers) and the condition selection of the step after that (registered
    // here; the next step computes its condition bits into rbits_q / cbit_q)
    logic [2:0] src_d, src_q;
    logic [4:0] opnd_d, opnd_q, cond_d;
    logic [2:0] rc_d, rc_q;
    logic [1:0] binv_sel_d, binv_sel_q, cin_sel_d, cin_sel_q;

    assign src_d      = word[svpwm_pkg::UcSrc +: svpwm_pkg::UcSrcW];
    assign opnd_d     = word[svpwm_pkg::UcOpnd +: svpwm_pkg::UcOpndW];
    assign rc_d       = word[svpwm_pkg::UcRc +: svpwm_pkg::UcRcW];
    assign cond_d     = word[svpwm_pkg::UcCond +: svpwm_pkg::UcCondW];
    assign binv_sel_d = word[svpwm_pkg::UcBinv +: svpwm_pkg::UcBinvW];
    assign cin_sel_d  = word[svpwm_pkg::UcCin +: svpwm_pkg::UcCinW];

    // ---- mode and conditions ---------------------------------------------------------------------------
    // the mode and DPWM decodes are registered (mode_i / dpwm_i hold from start_i on: valid from step 1,
    // and nothing reads them in the start clock: the own fields and the condition bits are gated by busy)
    logic [2:0] mode;
    logic [1:0] dpwm;
    logic       is_vf, is_ab, is_dq, is_th, is_err, is_xy, pred_ok;
    logic [5:0] mdec_d, mdec_q;          // {err, xy, th, dq, ab, vf}
    logic [1:0] dpdec_d, dpdec_q;        // {DPWM off, DPWM max}
    logic       dp60_d, dp60_q;          // DPWM1 (60 deg)

    // a mode the build lacks: the invalid code (zero vector, err); DPWM not built: SVPWM
    assign mode    = (mode_i <= 3'(svpwm_pkg::ModeDq) && !ModesBuilt[mode_i]) ? 3'(svpwm_pkg::ModeNotBuilt)
                                                                            : mode_i;
    assign dpwm    = HasDpwm ? dpwm_i : 2'(svpwm_pkg::DpwmOff);
    assign mdec_d  = {mode > 3'(svpwm_pkg::ModeDq),
                      (mode == 3'(svpwm_pkg::ModeAb)) || (mode == 3'(svpwm_pkg::ModeDq)),
                      (mode == 3'(svpwm_pkg::ModePolar)) || (mode == 3'(svpwm_pkg::ModeDq)),
                      mode == 3'(svpwm_pkg::ModeDq), mode == 3'(svpwm_pkg::ModeAb), mode == 3'(svpwm_pkg::ModeVf)};
    assign dpdec_d = {dpwm == 2'(svpwm_pkg::DpwmOff), dpwm == 2'(svpwm_pkg::DpwmMax)};
    assign dp60_d  = (dpwm == 2'(svpwm_pkg::Dpwm60));
    assign {is_err, is_xy, is_th, is_dq, is_ab, is_vf} = mdec_q;

    always_comb begin
      unique case (pred)
        3'(svpwm_pkg::PredTh): pred_ok = UsedPred[svpwm_pkg::PredTh] && is_th;
        3'(svpwm_pkg::PredAb): pred_ok = UsedPred[svpwm_pkg::PredAb] && is_ab;
        3'(svpwm_pkg::PredDq): pred_ok = UsedPred[svpwm_pkg::PredDq] && is_dq;
        3'(svpwm_pkg::PredXy): pred_ok = UsedPred[svpwm_pkg::PredXy] && is_xy;
        default:    pred_ok = 1'b1;
      endcase
    end

    logic [svpwm_pkg::CalcFlags-1:0] flags_d, flags_q;
    logic [2:0]           sec_d, sec_q;
    logic [5:0]           sel_d, sel;
    logic                 midneg_d, midneg;
    logic [31:0]          c;

    // Table 4-3 codes of the sector, registered from it (sel == sector_sel(sec_q of the clock before): the
    // builder places the out steps and the C_MIDSGN reads late enough; the ROM-like no-reset register loads
    // every clock, also in reset)
    svpwm_sector_sel u_sel (
      .sector_i (sec_q),
      .sel_o    (sel_d)
    );
    assign midneg_d = (sel_d[1:0] == 2'd3) || (sel_d[3:2] == 2'd3) || (sel_d[5:4] == 2'd3);
    always_ff @(posedge clk_i) begin
      sel    <= sel_d;
      midneg <= midneg_d;
    end

    // is_cls[j][ph]: phase ph's Table 4-3 code is of class hi (j = 0: code 0), lo (1: code 1) or mid (2: codes
    // 2, 3); the dead-time compensation inputs (InDhi, InDlo, InDmid) follow the sign of that class's phase
    logic [2:0] is_cls [3];
    for (genvar ph = 0; ph < 3; ph++) begin : gen_is_cls
      assign is_cls[0][ph] = sel[2*ph +: 2] == 2'd0;
      assign is_cls[1][ph] = sel[2*ph +: 2] == 2'd1;
      assign is_cls[2][ph] = sel[2*ph+1];
    end

    // the condition vector, and below the flags and the compare values, bit by bit in continuous
    // assignments: an always_comb that sets a default and then overwrites single bits of the same vector
    // re-triggers itself in Icarus 11 (a zero-time loop: the simulation hangs)
    for (genvar k = 0; k < 32; k++) begin : gen_c
      if (k < svpwm_pkg::CalcFlags)        begin : gen_flag assign c[k] = flags_q[k]; end
      else if (k == svpwm_pkg::CVf)        begin : gen_vf   assign c[k] = is_vf; end
      else if (k == svpwm_pkg::CXy)        begin : gen_xy   assign c[k] = is_xy; end
      else if (k == svpwm_pkg::CErr)       begin : gen_err  assign c[k] = is_err; end
      else if (k == svpwm_pkg::CMidsgn)    begin : gen_mid  assign c[k] = midneg ^ flags_q[svpwm_pkg::FFirst]; end
      else if (k == svpwm_pkg::CDq)        begin : gen_dq   assign c[k] = is_dq; end
      else if (k == svpwm_pkg::CNv1n)      begin : gen_nv1n assign c[k] = !flags_q[svpwm_pkg::FV1n]; end
      else if (k == svpwm_pkg::CNhalf)     begin : gen_nhf  assign c[k] = !flags_q[svpwm_pkg::FHalf]; end
      else                                 begin : gen_zero assign c[k] = 1'b0; end
    end

    // sector of the X, Y, Z signs (fixed.xyz_sector): q = (X, Z, -Y, -X, -Z, Y), the first s with
    // q_s >= 0 > q_s+1 (none: the zero vector, sector 0); sw_q: registered (the sector load reads it)
    logic [5:0] neg;
    logic [2:0] sw, sw_q, sw_mod3, sw1_mod3;
    assign neg = {flags_q[svpwm_pkg::FNy], flags_q[svpwm_pkg::FPz], flags_q[svpwm_pkg::FPx], flags_q[svpwm_pkg::FPy], flags_q[svpwm_pkg::FNz], flags_q[svpwm_pkg::FNx]};
    // (a priority chain, not a for loop in an always_comb: that one hung Icarus 11 in a zero-time loop)
    logic [5:0] edge_s;                   // edge_s[s]: q_s >= 0 > q_s+1
    assign edge_s = ~neg & {neg[0], neg[5:1]};
    assign sw = edge_s[0] ? 3'd0 : edge_s[1] ? 3'd1 : edge_s[2] ? 3'd2 :
                edge_s[3] ? 3'd3 : edge_s[4] ? 3'd4 : edge_s[5] ? 3'd5 : 3'd0;
    always_comb begin
      unique case (sw_q)
        3'd0, 3'd3: begin sw_mod3 = 3'd0; sw1_mod3 = 3'd1; end
        3'd1, 3'd4: begin sw_mod3 = 3'd1; sw1_mod3 = 3'd2; end
        default:    begin sw_mod3 = 3'd2; sw1_mod3 = 3'd0; end
      endcase
    end

    // minimum-pulse result word in {c, 0, thr, P, P - hthr} (fixed.snap_min_pulse)
    logic [2:0] snap;
    always_comb begin
      if (flags_q[svpwm_pkg::FS1])       snap = flags_q[svpwm_pkg::FS2] ? 3'd1 : 3'd2;
      else if (!flags_q[svpwm_pkg::FS3]) snap = !flags_q[svpwm_pkg::FS4] ? 3'd3 : 3'd4;
      else                    snap = 3'd0;
    end

    // ---- the adder -----------------------------------------------------------------------------------
    // sign_q: the sign of every step's sum, registered (in the carry chain's top cell); the flags and Q
    // take it one clock after their step, a BinvNsign operand (the division) is inverted by it two steps
    // after its step. ACC's top bit is sign_q, or top_q after a held step (a compare: the sum's sign is
    // not ACC's)
    logic [W-1:0] acc_q, ram_q, aux_d, aux_q, a_val, b_val, sum;
    logic [W-2:0] acc_lo_d, acc_lo_q;
    logic         b_ram_q, binv_d, binv_q, cin_d, cin_q, sign, sign_q;
    logic         held_d, held_q, top_d, top_q;

    assign acc_q    = {held_q ? top_q : sign_q, acc_lo_q};
    assign a_val    = aen_q ? (ash_q ? {acc_q[W-2:0], 1'b0} : acc_q) : '0;
    assign b_val    = (b_ram_q ? ram_q : aux_q) ^ {W{binv_q}};
    // carry select (timing: the adder pass RAM word -> B -> carry chain -> sign register is the calculator's
    // worst path): the low half and both versions of the high half (carry in 0 / 1) side by side, the high
    // half chosen by the low half's carry out, so no chain is longer than W - WL bits
    localparam int WL = W / 2;
    logic [WL:0]     sum_lo;
    logic [W-WL-1:0] sum_hi0, sum_hi1;
    assign sum_lo  = {1'b0, a_val[WL-1:0]} + {1'b0, b_val[WL-1:0]} + (WL+1)'(cin_q);
    assign sum_hi0 = a_val[W-1:WL] + b_val[W-1:WL];
    assign sum_hi1 = a_val[W-1:WL] + b_val[W-1:WL] + (W-WL)'(1);
    assign sum     = {sum_lo[WL] ? sum_hi1 : sum_hi0, sum_lo[WL-1:0]};
    assign sign     = sum[W-1];
    assign held_d   = !(busy && !hold);
    assign acc_lo_d = held_d ? acc_lo_q : sum[W-2:0];
    assign top_d    = held_d ? acc_q[W-1] : top_q;

    // ---- operand RAM ---------------------------------------------------------------------------------
    // the condition bits of the step after next, from the registered condition selection and the flags,
    // into registers (zero in the start clock: the selection is then the idle word's or stale)
    // (c[cond] as an AND-OR over the registered one-hot cond; RC_C's bit ORed in only at the address)
    logic [4:0]  raddr;
    logic [2:0]  rbits, rbits_d, rbits_q;
    logic        cbit, cbit_d, cbit_q, rcc_d, rcc_q;
    logic [31:0] cond_oh_d, cond_oh_q;
    assign cond_oh_d = (32'd1 << cond_d) & UsedCond;
    assign cbit      = |(cond_oh_q & c);
    always_comb begin
      unique case (rc_q)
        3'(svpwm_pkg::RcSw):    rbits = UsedRc[svpwm_pkg::RcSw] ? sw_mod3 : 3'd0;
        3'(svpwm_pkg::RcSw1):   rbits = UsedRc[svpwm_pkg::RcSw1] ? sw1_mod3 : 3'd0;
        3'(svpwm_pkg::RcSnap):  rbits = UsedRc[svpwm_pkg::RcSnap] ? snap : 3'd0;
        3'(svpwm_pkg::RcDpwm):  rbits = !UsedRc[svpwm_pkg::RcDpwm] ? 3'd0
                                      : {1'b0, dpdec_q[1], dpdec_q[0] || (dp60_q && !flags_q[svpwm_pkg::FDp60])};
        3'(svpwm_pkg::RcMerge): rbits = UsedRc[svpwm_pkg::RcMerge] ? {1'b0, is_err, is_xy} : 3'd0;
        default:     rbits = 3'd0;
      endcase
    end
    assign rbits_d = busy ? rbits : 3'd0;
    assign cbit_d  = busy && cbit;
    assign rcc_d   = busy && (rc_q == 3'(svpwm_pkg::RcC));
    assign raddr   = opnd_q | {2'd0, rbits_q[2:1], rbits_q[0] | (rcc_q && cbit_q)};

    svpwm_calc_ram #(.Width(W)) u_ram (
      .clk_i   (clk_i),
      .we_i    (we && pred_ok),
      .waddr_i (dst),
      .wdata_i (acc_q),
      .raddr_i (raddr),
      .rdata_o (ram_q)
    );

    // ---- sine ROM: address from ANG[15:8] = i of the clock before (the four addresses registered) -------
    logic [15:0] ang_d, ang_q, rom_q;
    logic [8:0]  rom_addr, ri_d, ri_q, ri1_d, ri1_q, rn_d, rn_q, rn1_d, rn1_q;
    logic [7:0]  ang_i;
    assign ang_i = ang_q[15:8];
    assign ri_d  = {1'b0, ang_i};
    assign ri1_d = {1'b0, ang_i} + 9'd1;
    assign rn_d  = 9'd256 - {1'b0, ang_i};
    assign rn1_d = 9'd255 - {1'b0, ang_i};
    // (an AND-OR of the misc code's ROM selections, not gated by busy: the word read while idle, word 0,
    // has no misc action; 0 otherwise, as rsel)
    logic [3:0] rs;
    logic [3:0] misc_code;
    assign misc_code = word[svpwm_pkg::UcMisc +: svpwm_pkg::UcMiscW];
    assign rs = {misc_code == 4'(svpwm_pkg::MiscRomN1), misc_code == 4'(svpwm_pkg::MiscRomN),
                 misc_code == 4'(svpwm_pkg::MiscRomI1), misc_code == 4'(svpwm_pkg::MiscRomI)};
    assign rom_addr = ({9{rs[0]}} & ri_q) | ({9{rs[1]}} & ri1_q) | ({9{rs[2]}} & rn_q) | ({9{rs[3]}} & rn1_q);

    sine_rom u_rom (
      .clk_i  (clk_i),
      .addr_i (rom_addr),
      .data_o (rom_q)
    );

    // ---- multiplier ------------------------------------------------------------------------------------
    logic [15:0] ma_d, mb_d;
    logic [31:0] p;

    // a multiplier operand: 2^16 (a dwell time of the whole period) is capped at 0xFFFF (fixed.T_CAP)
    function automatic logic [15:0] sat16(input logic [16:0] x);
      sat16 = x[16] ? 16'hFFFF : x[15:0];
    endfunction

    always_comb begin
      ma_d = sat16(mas ? acc_q[16:0] : b_val[16:0]);
      unique case (mbs)
        2'(svpwm_pkg::MbFr):  mb_d = {8'd0, ang_q[7:0]};
        2'(svpwm_pkg::MbAcc): mb_d = sat16(acc_q[16:0]);
        default:   mb_d = sat16(b_val[16:0]);
      endcase
    end

    svpwm_mul #(.Dsp(Dsp)) u_mul (
      .clk_i  (clk_i),
      .rst_ni (rst_ni),
      .la_i   (mla),
      .a_i    (ma_d),
      .lb_i   (mlb),
      .b_i    (mb_d),
      .p_o    (p)
    );

    // ---- AUX: the next step's non-RAM operand -------------------------------------------------------------
    // the input the word selects (the operand of the step after next), registered sign-extended in in_q
    // per phase: the compensation by its current sign plus its carry, registered (the inputs hold from the
    // start; the program reads these late), then per class the phase's value (dtc_in)
    // (|hd| <= 2^(DtWidth-1), |carry| <= 2^DtWidth: DtWidth + 2 bits signed)
    logic [15:0]   in_sel;
    logic [EW-1:0] hdf_w, mhdr_q;
    logic [EW-1:0] dpe_d [3];
    logic [EW-1:0] dpe_q [3];
    logic [EW-1:0] dtc_d [3];
    logic [EW-1:0] dtc_in [3];
    logic          in_signed;
    // -hdr registered (every clock; hdr_i holds from the start, the program reads the inputs below late:
    // the negation's carry chain before the sum's was a worst path)
    assign hdf_w  = EW'(hdf_i);
    always_ff @(posedge clk_i) mhdr_q <= EW'(0) - EW'(hdr_i);
    for (genvar ph = 0; ph < 3; ph++) begin : gen_dpe
      assign dpe_d[ph] = (HasDtc ? (isign_i[ph] ? hdf_w : mhdr_q) : EW'(0))
                       + ((HasCarry && carry_en_i) ? carry_i[ph*EW +: EW] : EW'(0));
      always_ff @(posedge clk_i) dpe_q[ph] <= dpe_d[ph];
    end
    // (registered again: sel -> class -> this multiplexer -> the input multiplexer -> in_q was a worst path;
    // the program reads these inputs five steps after a sector change at the earliest: calc_prog.Builder)
    for (genvar j = 0; j < 3; j++) begin : gen_dtc_in
      assign dtc_d[j] = ({EW{is_cls[j][0]}} & dpe_q[0]) | ({EW{is_cls[j][1]}} & dpe_q[1])
                      | ({EW{is_cls[j][2]}} & dpe_q[2]);
      always_ff @(posedge clk_i) dtc_in[j] <= dtc_d[j];
    end
    logic [16:0] in_d, in_q;
    always_comb begin
      in_sel    = 16'd0;
      in_signed = 1'b0;
      unique case (opnd_d[3:0])
        4'(svpwm_pkg::InM):      in_sel = m_i;
        4'(svpwm_pkg::InTheta):  in_sel = HasTheta ? theta_i : 16'd0;
        4'(svpwm_pkg::InV1):     begin in_sel = HasXy ? v1_i : 16'd0; in_signed = HasXy; end
        4'(svpwm_pkg::InV2):     begin in_sel = HasXy ? v2_i : 16'd0; in_signed = HasXy; end
        4'(svpwm_pkg::InBoost):  in_sel = HasVf ? vf_boost_i : 16'd0;
        4'(svpwm_pkg::InSlope):  in_sel = HasVf ? vf_slope_i : 16'd0;
        4'(svpwm_pkg::InMmax):   in_sel = HasVf ? vf_mmax_i : 16'd0;
        4'(svpwm_pkg::InFabs):   in_sel = HasVf ? fabs_i : 16'd0;
        4'(svpwm_pkg::InPeriod): in_sel = 16'(period_i);
        4'(svpwm_pkg::InThr):    in_sel = 16'(thr_i);
        // the dead-time compensation of the class's phase: + hdf for a negative current, else - hdr
        4'(svpwm_pkg::InDhi):    begin in_sel = 16'($signed(dtc_in[0])); in_signed = 1'b1; end
        4'(svpwm_pkg::InDlo):    begin in_sel = 16'($signed(dtc_in[1])); in_signed = 1'b1; end
        4'(svpwm_pkg::InDmid):   begin in_sel = 16'($signed(dtc_in[2])); in_signed = 1'b1; end
        4'(svpwm_pkg::InMv):     in_sel = (HasSix && om_i && !is_xy) ? 16'(svpwm_pkg::MVertex) : 16'hFFFF;
        default:      in_sel = 16'd0;
      endcase
      if (!UsedIsel[{1'b0, opnd_d[3:0]}]) begin   // an input the program never reads: no arm
        in_sel    = 16'd0;
        in_signed = 1'b0;
      end
    end
    assign in_d = {in_signed && in_sel[15], in_sel};

    logic [31:0] p_sh;
    logic        rbit;
    always_comb begin
      unique case (opnd_q[1:0])
        2'd0:    begin p_sh = p >> svpwm_pkg::Psh0; rbit = p[svpwm_pkg::Psh0 - 1]; end
        2'd1:    begin p_sh = UsedPsh[1] ? p >> svpwm_pkg::Psh1 : '0;
                       rbit = UsedPsh[1] && p[svpwm_pkg::Psh1 - 1]; end
        2'd2:    begin p_sh = UsedPsh[2] ? p >> svpwm_pkg::Psh2 : '0;
                       rbit = UsedPsh[2] && p[svpwm_pkg::Psh2 - 1]; end
        default: begin p_sh = p;         rbit = 1'b0;       end
      endcase
    end

    logic signed [W-1:0] acc_s;
    logic [15:0]         q_d, q_q;
    assign acc_s = acc_q;
    always_comb begin
      unique case (src_q)
        3'(svpwm_pkg::AsRom):  aux_d = UsedSrc[svpwm_pkg::AsRom] ? W'(rom_q) : '0;
        3'(svpwm_pkg::AsProd): aux_d = UsedSrc[svpwm_pkg::AsProd] ? W'(p_sh) : '0;
        3'(svpwm_pkg::AsIn):   aux_d = UsedSrc[svpwm_pkg::AsIn] ? W'($signed(in_q)) : '0;
        3'(svpwm_pkg::AsShr9): aux_d = UsedSrc[svpwm_pkg::AsShr9] ? W'(acc_s >>> 9) : '0;
        3'(svpwm_pkg::AsShr1): aux_d = UsedSrc[svpwm_pkg::AsShr1] ? W'(acc_s >>> 1) : '0;
        3'(svpwm_pkg::AsQ):    aux_d = UsedSrc[svpwm_pkg::AsQ] ? W'(q_q) : '0;
        3'(svpwm_pkg::AsAng):  aux_d = UsedSrc[svpwm_pkg::AsAng] ? W'(ang_q) : '0;
        default:    aux_d = '0;
      endcase
    end

    always_comb begin
      unique case (binv_sel_q)
        2'(svpwm_pkg::BinvYes):   binv_d = 1'b1;
        2'(svpwm_pkg::BinvC):     binv_d = UsedBinv[svpwm_pkg::BinvC] && cbit_q;
        2'(svpwm_pkg::BinvNsign): binv_d = UsedBinv[svpwm_pkg::BinvNsign] && !sign_q;
        default:       binv_d = 1'b0;
      endcase
      unique case (cin_sel_q)
        2'(svpwm_pkg::Cin1):    cin_d = 1'b1;
        2'(svpwm_pkg::CinBinv): cin_d = binv_d;
        2'(svpwm_pkg::CinRnd):  cin_d = UsedCin[svpwm_pkg::CinRnd]
                                        && (((src_q == 3'(svpwm_pkg::AsProd)) && rbit) ^ binv_d);
        default:     cin_d = 1'b0;
      endcase
    end

    // ---- flags, Q, angle, sector, compare values -----------------------------------------------------
    logic [3*CntWidth-1:0] cmp_d, cmp_q;
    logic                  done_q;

    // a flag set / Q shift acts one clock after its step, with sign_q (the builder waits for it)
    logic       fset_q, qsh_q;
    logic [4:0] fidx_q;
    for (genvar k = 0; k < svpwm_pkg::CalcFlags; k++) begin : gen_flags
      assign flags_d[k] = (UsedFlag[k] && fset_q && fidx_q == 5'(k)) ? sign_q : flags_q[k];
    end
    assign q_d = qsh_q ? {q_q[14:0], !sign_q} : q_q;

    // DQ: the sector of X, Y, Z counts from theta's sector: (sw + sector) mod 6
    logic [3:0] sec_sum;
    logic [2:0] sec_dq;
    assign sec_sum = {1'b0, sw_q} + {1'b0, sec_q};
    assign sec_dq  = (sec_sum >= 4'd6) ? 3'(sec_sum - 4'd6) : sec_sum[2:0];

    always_comb begin
      ang_d = ang_q;
      sec_d = sec_q;
      if (!busy && start_i) begin
        ang_d = angle_i;
        sec_d = sector_i;
      end
      if (ald && pred_ok) ang_d = acc_q[15:0];
      unique case (sec_op)
        2'(svpwm_pkg::SecTheta): if (UsedSec[svpwm_pkg::SecTheta] && pred_ok) sec_d = acc_q[18:16];
        2'(svpwm_pkg::SecXyz):   if (UsedSec[svpwm_pkg::SecXyz] && pred_ok) sec_d = is_dq ? sec_dq : sw_q;
        2'(svpwm_pkg::SecErr):   if (UsedSec[svpwm_pkg::SecErr] && is_err) sec_d = 3'd0;
        default:      ;
      endcase
    end

    // the volt-second carry (fixed.snap_carry): the command the minimum-pulse rule snaps is the value
    // written to its RAM word (RSnap); the carry is command - snapped (the ACC of the out step), limited to
    // +-hthr = +-ceil(thr / 2), in three registered stages (the difference, the two limit compares, the
    // choice: carry_o is valid two clocks after done_o). The command lies in [-3 2^(DtWidth-1),
    // P + 3 2^(DtWidth-1)]: CntWidth + 2 bits signed (DtWidth + 2 <= CntWidth)
    localparam int CW = CntWidth + 2;
    logic [CW-1:0] cmd_d, cmd_q, cd_d, cd_q, wdata_q;
    logic          snap_we_d, snap_we_q;  // the RSnap write of the clock before (cmd_q follows a clock
                                          // later: the word's decode -> 18 enables was a worst path)
    logic [EW-1:0] ecar, hthr_d, hthr_q, hthr2_q, mhthr_d, mhthr_q, cd2_q;
    logic          c_hi_d, c_hi_q, c_lo_d, c_lo_q;
    logic [2:0]    ldp_d, ldp_q, ldp2_q;      // the phases of the out step one / two clocks before
    assign snap_we_d = we && pred_ok && dst == 5'(svpwm_pkg::RSnap);
    assign cmd_d     = snap_we_q ? wdata_q : cmd_q;
    assign cd_d    = cmd_q - acc_q[CW-1:0];
    assign hthr_d  = EW'(({1'b0, thr_i} + 1'b1) >> 1);
    assign mhthr_d = EW'(0) - hthr_q;
    assign c_hi_d  = $signed(cd_q) > $signed(CW'(hthr_q));
    assign c_lo_d  = $signed(cd_q) < $signed({{(CW-EW){mhthr_q[EW-1]}}, mhthr_q});
    assign ecar    = c_hi_q ? hthr2_q : c_lo_q ? mhthr_q : cd2_q;
    // (no reset: hthr from thr_i, which holds from the start; the stages follow the out steps)
    always_ff @(posedge clk_i) begin
      hthr_q  <= hthr_d;
      mhthr_q <= mhthr_d;
      hthr2_q <= hthr_q;                      // (the limits the choice uses: from thr_i before done_o)
      c_hi_q  <= c_hi_d;
      c_lo_q  <= c_lo_d;
      cd2_q   <= cd_q[EW-1:0];
      ldp2_q  <= ldp_q;
    end

    // out: the phases whose Table 4-3 code is of this class take ACC (0: the highest, 1: the lowest, 2 / 3:
    // the middle compare value) and their carry
    logic [3*EW-1:0] car_d, car_q;
    for (genvar ph = 0; ph < 3; ph++) begin : gen_out
      logic [1:0] cls;
      logic       ld;
      assign cls = (sel[2*ph +: 2] == 2'd0) ? 2'(svpwm_pkg::OutHi)
                 : (sel[2*ph +: 2] == 2'd1) ? 2'(svpwm_pkg::OutLo) : 2'(svpwm_pkg::OutMid);
      assign ld  = out_op != 2'(svpwm_pkg::OutNone) && out_op == cls;
      assign cmp_d[ph*CntWidth +: CntWidth] = ld ? acc_q[CntWidth-1:0] : cmp_q[ph*CntWidth +: CntWidth];
      assign ldp_d[ph] = ld;
      assign car_d[ph*EW +: EW] = ldp2_q[ph] ? ecar : car_q[ph*EW +: EW];
    end

    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        pc_q    <= '0;
        busy_q  <= 1'b0;
        acc_lo_q <= '0;
        aen_q    <= 1'b0;
        ash_q    <= 1'b0;
        sign_q   <= 1'b0;
        held_q   <= 1'b1;
        top_q    <= 1'b0;
        fset_q   <= 1'b0;
        fidx_q   <= '0;
        qsh_q    <= 1'b0;
        cond_oh_q <= '0;
        rcc_q    <= 1'b0;
        mdec_q   <= '0;
        dpdec_q  <= '0;
        dp60_q   <= 1'b0;
        aux_q   <= '0;
        b_ram_q <= 1'b0;
        src_q      <= '0;
        opnd_q     <= '0;
        binv_sel_q <= '0;
        cin_sel_q  <= '0;
        rc_q       <= '0;
        rbits_q    <= '0;
        cbit_q     <= 1'b0;
        in_q       <= '0;
        sw_q       <= '0;
        ri_q       <= '0;
        ri1_q      <= '0;
        rn_q       <= '0;
        rn1_q      <= '0;
        binv_q  <= 1'b0;
        cin_q   <= 1'b0;
        flags_q <= '0;
        q_q     <= '0;
        ang_q   <= '0;
        sec_q   <= '0;
        cmp_q   <= '0;
        car_q   <= '0;
        cmd_q   <= '0;
        wdata_q <= '0;
        snap_we_q <= 1'b0;
        cd_q    <= '0;
        ldp_q   <= '0;
        done_q  <= 1'b0;
      end else begin
        pc_q    <= pc_d;
        busy_q  <= busy_d;
        acc_lo_q <= acc_lo_d;
        aen_q    <= aen_d;
        ash_q    <= ash_d;
        sign_q   <= sign;
        held_q   <= held_d;
        top_q    <= top_d;
        fset_q   <= fset;
        fidx_q   <= dst;
        qsh_q    <= qsh;
        cond_oh_q <= cond_oh_d;
        rcc_q    <= rcc_d;
        mdec_q   <= mdec_d;
        dpdec_q  <= dpdec_d;
        dp60_q   <= dp60_d;
        aux_q   <= aux_d;
        b_ram_q <= (src_q == 3'(svpwm_pkg::AsNone));
        src_q      <= src_d;
        opnd_q     <= opnd_d;
        binv_sel_q <= binv_sel_d;
        cin_sel_q  <= cin_sel_d;
        rc_q       <= rc_d;
        rbits_q    <= rbits_d;
        cbit_q     <= cbit_d;
        in_q       <= in_d;
        sw_q       <= sw;
        ri_q       <= ri_d;
        ri1_q      <= ri1_d;
        rn_q       <= rn_d;
        rn1_q      <= rn1_d;
        binv_q  <= binv_d;
        cin_q   <= cin_d;
        flags_q <= flags_d;
        q_q     <= q_d;
        ang_q   <= ang_d;
        sec_q   <= sec_d;
        cmp_q   <= cmp_d;
        car_q   <= car_d;
        cmd_q   <= cmd_d;
        wdata_q <= acc_q[CW-1:0];
        snap_we_q <= snap_we_d;
        cd_q    <= cd_d;
        ldp_q   <= ldp_d;
        done_q  <= done && !abort_i;
      end
    end

    assign busy_o   = busy;
    assign done_o   = done_q;
    assign sector_o = sec_q;
    assign cmp_o    = cmp_q;
    assign carry_o  = car_q;
    assign sat_o    = !flags_q[svpwm_pkg::FSatn];
    assign err_o    = (mode > 3'(svpwm_pkg::ModeDq));   // (from mode_i itself, as the other results: not the
                                                        // registered decode, which lags mode_i by a clock)

    logic unused;
    assign unused = ^{p_sh, rsel, acc_q[W-1:CW]};          // (rsel: the ROM address decodes the misc code itself)
  end

endmodule

`default_nettype wire
