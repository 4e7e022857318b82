// SPDX-License-Identifier: Apache-2.0
// tb_svpwm_calc: unit harness around svpwm_calc (the core's one calculator). Generates the clock (10 ns)
// and checks the handshake on every clock against a reference of it, so the cocotb test only wakes on
// events (start, done). The reference: start_i in cycle c (sampled by the edge ending c) is accepted when
// idle and abort_i is low; busy_o is high in cycles c+1 .. c+L-1, done_o is high in cycle c+L (L = latency_i)
// only; abort_i returns to idle at once (no done_o); the done cycle is idle. Sticky flags until rst_ni:
//   chk_o[0]  busy_o differs from the reference (start not taken / ignored, busy too short / long, abort)
//   chk_o[1]  done_o differs from the reference (missing, early, late, extra, longer than one clock)
//   chk_o[2]  the testbench broke the input rule: an input other than sector_i / angle_i changed while
//             busy (checked at every edge the calculator computes on; thr_i, which may arrive one clock
//             after start_i, from the edge ending the clock after the start on (Compact = 0); a self-check of
//             the stimulus)
// err_cyc_o: the clock count at the first flag (0: none). Results (sector_o, cmp_o, sat_o, err_o) are
// defined only in the done cycle; the test compares them there; carry_o from the second clock after it (the
// calculator's two registered stages after its last out step) until the next computation's out steps.
// latency_i: the expected start -> done_o clocks, driven by the test (its LATENCY, from the model), held from
// reset on.
// Vector player (the test's run_vectors): the test writes one record per vector (the vector, the model's
// expected results, the schedule around it: an aborted junk computation or an idle gap before it, the
// sector_i / angle_i scrambles and start_i while busy) to a file, names it on stim_file_i with the count on
// stim_n_i and raises play_i; the harness then drives every input of the calculator itself (on the falling
// edges, as the test does) and checks in its own clock: busy_o, done_o one clock after each start; busy_o,
// done_o, sector_o, cmp_o, sat_o, err_o === (0, 1, the expected results) 1 ns after the edge that must raise
// done_o; carry_o === the expected carry 1 ns after the second rising edge after that one (done_o + 2: the
// record after is then running already -- its start in the done cycle -- but its out steps, the last steps
// of its program, or an aborted junk computation's, come much later); busy_o, done_o low after an abort and
// in the clock after. In the first clock of every record (the done cycle of the vector before) thr_i keeps
// its value and the record's own thr_i follows one clock later (the late arrival the calculator allows):
// the carry limit of the vector before, +ceil(thr / 2), is registered from thr_i in its done cycle (Compact
// = 1: not so; carry_o is 0 there, and the compact datapath reads thr_i with start_i). It ends
// with start_i low for two clocks
// and toggles play_end_o -- after the last record, or after the first record with a failed check (a broken
// RTL fails in the time of the vectors up to it, not of the whole set: scripts/mutate.py); fail_n_o counts
// that record's failed checks, fail_idx_o / fail_what_o / fail_got_o describe the
// first (what: 1 busy_o, done_o one clock after the start, 2 the results, 3 not idle after an abort, 4 an
// abort's clock after, 5 carry_o at done_o + 2: fail_car_o; checked while the record after runs, so the
// player stops after that one and fail_n_o may count a check of it). The checker above sees the inputs the
// calculator gets (ports or player).
`timescale 1ns / 1ps
`default_nettype none

module tb_svpwm_calc #(
  parameter logic [31:0] Features = svpwm_pkg::CfgFull,   // the build (its Dsp bit 0: the serial unit)
  parameter int CntWidth = 16,
  parameter int DtWidth  = 10,
  parameter int MaxVec   = 65600              // player: records per run
) (
  input  logic [15:0]           latency_i,
  input  logic                  rst_ni,
  input  logic                  start_i,
  input  logic                  abort_i,
  input  logic [2:0]            mode_i,
  input  logic [2:0]            sector_i,
  input  logic [15:0]           angle_i,
  input  logic [15:0]           theta_i,
  input  logic [15:0]           m_i,
  input  logic [15:0]           fabs_i,
  input  logic signed [15:0]    v1_i,
  input  logic signed [15:0]    v2_i,
  input  logic [15:0]           vf_boost_i,
  input  logic [15:0]           vf_slope_i,
  input  logic [15:0]           vf_mmax_i,
  input  logic [1:0]            dpwm_i,
  input  logic                  om_i,
  input  logic [CntWidth-1:0]   period_i,
  input  logic [DtWidth:0]      thr_i,
  input  logic [2:0]            isign_i,
  input  logic [DtWidth-1:0]    hdr_i,
  input  logic [DtWidth-1:0]    hdf_i,
  input  logic [3*DtWidth+5:0]  carry_i,
  input  logic                  carry_en_i,
  input  logic                  play_i,       // rising: run the player (stim_file_i, stim_n_i)
  input  logic [8*64-1:0]       stim_file_i,  // file name (ASCII, right aligned, <= 64 characters)
  input  logic [31:0]           stim_n_i,     // records in the file
  output logic                  clk,
  output logic                  busy_o,
  output logic                  done_o,
  output logic [2:0]            sector_o,
  output logic [3*CntWidth-1:0] cmp_o,
  output logic                  sat_o,
  output logic                  err_o,
  output logic [3*DtWidth+5:0]  carry_o,
  output logic [2:0]            chk_o,
  output logic [31:0]           err_cyc_o,
  output logic                  play_end_o,   // toggles when the player has finished
  output logic [31:0]           fail_n_o,     // player: failed checks
  output logic [31:0]           fail_idx_o,   // player: record of the first failed check
  output logic [2:0]            fail_what_o,  // player: kind of the first failed check (header)
  output logic [3*CntWidth+6:0] fail_got_o,   // player: {busy, done, sector, cmp, sat, err} then
  output logic [3*DtWidth+5:0]  fail_car_o    // player: carry_o then
);

  // the tiny build (TRANSITIONAL: the compact core's own datapath, which reads thr_i with start_i)
  localparam bit Compact = svpwm_pkg::is_tiny(Features);

  localparam int EW        = DtWidth + 2;    // carry per phase, signed
  localparam int HeldWidth = 3 + 16 * 8 + 2 + CntWidth + 3 + 2 * DtWidth + 1 + 3 * EW + 1;   // (thr_i apart)

  initial clk = 1'b0;
  always #5 clk = ~clk;

  // ---- the calculator's inputs: from the ports, or from the player while it runs ----
  localparam int PinW = 280;                 // one input set in a record (see the player below)
  logic                  playing;
  logic                  p_start, p_abort;
  logic [PinW-1:0]       p_pins;
  logic                  start, abort;
  logic [2:0]            mode, sector;
  logic [15:0]           angle, theta, m, fabs, v1, v2, vf_boost, vf_slope, vf_mmax;
  logic [1:0]            dpwm;
  logic [CntWidth-1:0]   period;
  logic [DtWidth:0]      thr;
  logic [2:0]            isign;
  logic [DtWidth-1:0]    hdr, hdf;
  logic                  om, carry_en;
  logic [3*EW-1:0]       carry;

  assign start    = playing ? p_start : start_i;
  assign abort    = playing ? p_abort : abort_i;
  assign mode     = playing ? p_pins[2:0]     : mode_i;
  assign sector   = playing ? p_pins[5:3]     : sector_i;
  assign angle    = playing ? p_pins[21:6]    : angle_i;
  assign theta    = playing ? p_pins[37:22]   : theta_i;
  assign m        = playing ? p_pins[53:38]   : m_i;
  assign fabs     = playing ? p_pins[69:54]   : fabs_i;
  assign v1       = playing ? p_pins[85:70]   : v1_i;
  assign v2       = playing ? p_pins[101:86]  : v2_i;
  assign vf_boost = playing ? p_pins[117:102] : vf_boost_i;
  assign vf_slope = playing ? p_pins[133:118] : vf_slope_i;
  assign vf_mmax  = playing ? p_pins[149:134] : vf_mmax_i;
  assign dpwm     = playing ? p_pins[151:150] : dpwm_i;
  assign period   = playing ? p_pins[152 +: CntWidth] : period_i;
  assign thr      = playing ? p_pins[168 +: DtWidth + 1] : thr_i;
  assign isign    = playing ? p_pins[186:184] : isign_i;
  assign hdr      = playing ? p_pins[192 +: DtWidth] : hdr_i;
  assign hdf      = playing ? p_pins[208 +: DtWidth] : hdf_i;
  assign om       = playing ? p_pins[224]     : om_i;
  assign carry_en = playing ? p_pins[225]     : carry_en_i;
  for (genvar ph = 0; ph < 3; ph++) begin : gen_carry
    assign carry[ph*EW +: EW] = playing ? p_pins[232 + 16 * ph +: EW] : carry_i[ph*EW +: EW];
  end

  svpwm_calc #(.Features(Features), .CntWidth(CntWidth), .DtWidth(DtWidth)) u_dut (
    .clk_i      (clk),
    .rst_ni     (rst_ni),
    .start_i    (start),
    .abort_i    (abort),
    .mode_i     (mode),
    .sector_i   (sector),
    .angle_i    (angle),
    .theta_i    (theta),
    .m_i        (m),
    .fabs_i     (fabs),
    .v1_i       (v1),
    .v2_i       (v2),
    .vf_boost_i (vf_boost),
    .vf_slope_i (vf_slope),
    .vf_mmax_i  (vf_mmax),
    .dpwm_i     (dpwm),
    .om_i       (om),
    .period_i   (period),
    .thr_i      (thr),
    .isign_i    (isign),
    .hdr_i      (hdr),
    .hdf_i      (hdf),
    .carry_i    (carry),
    .carry_en_i (carry_en),
    .busy_o     (busy_o),
    .done_o     (done_o),
    .sector_o   (sector_o),
    .cmp_o      (cmp_o),
    .sat_o      (sat_o),
    .err_o      (err_o),
    .carry_o    (carry_o)
  );

  // ---- handshake reference and checker (header) ----
  logic [HeldWidth-1:0] held, held_q;
  logic [DtWidth:0]     thr_q;             // thr_i: latched at the edge ending the clock after the start
                                           // (Compact = 1: at the start, its datapath reads it then)
  int unsigned          ref_st, cyc;       // ref_st: 0 idle, k = k-th clock after the accepted start
  logic                 ref_done;

  assign held = {mode, theta, m, fabs, v1, v2, vf_boost, vf_slope, vf_mmax, dpwm, period, isign, hdr, hdf, om,
                 carry, carry_en};
  logic held_bad;
  assign held_bad = ref_st != 0 && (held != held_q || ((Compact || ref_st >= 2) && thr != thr_q));

  always @(posedge clk or negedge rst_ni) begin
    if (!rst_ni) begin
      chk_o     <= '0;
      err_cyc_o <= '0;
      ref_st    <= 0;
      ref_done  <= 1'b0;
      held_q    <= '0;
      thr_q     <= '0;
      cyc       <= 0;
    end else begin
      cyc <= cyc + 1;
      // the outputs of the cycle this edge ends against the reference of that cycle
      if (busy_o != (ref_st != 0)) chk_o[0] <= 1'b1;
      if (done_o != ref_done)      chk_o[1] <= 1'b1;
      if (held_bad)                chk_o[2] <= 1'b1;
      if (err_cyc_o == 0 && (busy_o != (ref_st != 0) || done_o != ref_done || held_bad))
        err_cyc_o <= cyc + 1;
      if (ref_st == 1 && !Compact) thr_q <= thr;
      // the reference's next cycle
      ref_done <= 1'b0;
      if (abort) begin
        ref_st <= 0;
      end else if (ref_st == 32'(latency_i) - 1) begin
        ref_st   <= 0;
        ref_done <= 1'b1;
      end else if (ref_st != 0) begin
        ref_st <= ref_st + 1;
      end else if (start) begin
        ref_st <= 1;
        held_q <= held;
        thr_q  <= thr;
      end
    end
  end

  // ---- vector player (header) ----
  // A record (test_svpwm_calc.py: REC_FIELDS), from bit 0: the control word (CtlW bits), the vector's
  // inputs, junk A (the aborted computation's inputs, or the idle gap's), junk B (the inputs after an
  // abort). An input set (PinW bits): mode[2:0], sector[5:3], angle[21:6], theta, m, fabs, v1, v2, vf_boost,
  // vf_slope, vf_mmax (16 bits each from bit 22), dpwm[151:150], period[152 +: CntWidth], thr[168 +: DtWidth+1],
  // isign[186:184], hdr[192 +: DtWidth], hdf[208 +: DtWidth], om[224], carry_en[225], carry a, b, c
  // [232 + 16 ph +: DtWidth + 2].
  localparam int CtlW = 192;
  localparam int RecW = CtlW + 3 * PinW;
  logic [RecW-1:0] stim [MaxVec];

  // control word fields
  localparam int CPre  = 0;     // 2: 0 none, 1 an aborted junk computation, 2 an idle gap
  localparam int CAk   = 2;     // 9: the abort k clocks after the junk start (0: with start_i)
  localparam int CGap  = 11;    // 2: idle gap clocks (1..3)
  localparam int CAst  = 13;    // 1: start_i while the junk computation is busy
  localparam int CAsec = 14;    // 3: sector_i, angle_i while the junk computation is busy
  localparam int CAang = 17;    // 16
  localparam int CMid  = 33;    // 1: scramble again mid-computation
  localparam int CMk   = 34;    // 9: ... at falling edge k after the start (+ 2 ns)
  localparam int CMst  = 43;    // 1: start_i then
  localparam int CMsec = 44;    // 3
  localparam int CMang = 47;    // 16
  localparam int CSsec = 63;    // 3: sector_i, angle_i from one clock after the start (start_i high)
  localparam int CSang = 66;    // 16
  localparam int CEsec = 82;    // 3: expected sector_o
  localparam int CEc   = 85;    // 3 x 16: expected C_a, C_b, C_c
  localparam int CEsat = 133;   // 1: expected sat_o
  localparam int CEerr = 134;   // 1: expected err_o
  localparam int CEcar = 135;   // 3 x 16: expected carry_o a, b, c (DtWidth + 2 bits each)
  localparam int PThr  = 168;   // the thr field of an input set (16 bits)

  logic [RecW-1:0]       rec;
  logic [3*CntWidth-1:0] exp_cmp;
  logic [3*CntWidth+6:0] got;
  logic [15:0]           thr_prev;
  int unsigned           gi, rest, mid;
  // carry_o check, done_o + 2 (armed by the player at the done check, while the next record runs)
  int unsigned           car_cnt, car_idx;
  logic [3*EW-1:0]       car_exp;

  function automatic logic [3*CntWidth+6:0] outputs();
    return {busy_o, done_o, sector_o, cmp_o, sat_o, err_o};
  endfunction

  task automatic fail(input int unsigned idx, input logic [2:0] what);
    if (fail_n_o == 0) begin
      fail_idx_o  = idx;
      fail_what_o = what;
      fail_got_o  = outputs();
      fail_car_o  = carry_o;
    end
    fail_n_o = fail_n_o + 1;
  endtask

  always @(posedge clk) begin
    if (car_cnt != 0) begin
      car_cnt = car_cnt - 1;
      if (car_cnt == 0) begin
        #1;                                               // 1 ns after the second rising edge after done_o
        if (carry_o !== car_exp) fail(car_idx, 3'd5);
      end
    end
  end

  initial begin
    playing     = 1'b0;
    p_start     = 1'b0;
    p_abort     = 1'b0;
    p_pins      = '0;
    play_end_o  = 1'b0;
    fail_n_o    = 0;
    fail_idx_o  = 0;
    fail_what_o = 0;
    fail_got_o  = '0;
    fail_car_o  = '0;
    car_cnt     = 0;
    car_idx     = 0;
    car_exp     = '0;
  end

  always @(posedge play_i) begin
    $readmemh(stim_file_i, stim, 0, stim_n_i - 1);
    fail_n_o    = 0;
    fail_idx_o  = 0;
    fail_what_o = 0;
    fail_got_o  = '0;
    fail_car_o  = '0;
    car_cnt     = 0;
    p_start     = 1'b0;
    p_abort     = 1'b0;
    p_pins      = {PinW{1'b0}};
    playing     = 1'b1;
    @(negedge clk);
    for (gi = 0; gi < stim_n_i && fail_n_o == 0; gi++) begin   // up to the first vector that fails
      rec = stim[gi];
      thr_prev = p_pins[PThr +: 16];                      // thr_i in the record's first clock (header)
      if (rec[CPre +: 2] == 2'd1) begin                  // an aborted junk computation
        p_start = 1'b1;
        p_pins  = rec[CtlW + PinW +: PinW];
        if (!Compact) p_pins[PThr +: 16] = thr_prev;
        p_abort = (rec[CAk +: 9] == 9'd0);
        @(negedge clk);
        p_pins[PThr +: 16] = rec[CtlW + PinW + PThr +: 16];
        if (rec[CAk +: 9] != 9'd0) begin
          p_start        = rec[CAst];
          p_pins[5:3]    = rec[CAsec +: 3];
          p_pins[21:6]   = rec[CAang +: 16];
          repeat (32'(rec[CAk +: 9]) - 1) @(negedge clk);
          #2;                                           // 2 ns after falling edge k (before rising edge k)
          p_abort = 1'b1;
          @(negedge clk);
        end
        p_start = 1'b0;
        p_pins  = rec[CtlW + 2 * PinW +: PinW];
        p_abort = 1'b0;
        if (busy_o !== 1'b0 || done_o !== 1'b0) fail(gi, 3'd3);
        @(negedge clk);
        if (busy_o !== 1'b0 || done_o !== 1'b0) fail(gi, 3'd4);
      end else if (rec[CPre +: 2] == 2'd2) begin         // an idle gap, every input scrambled
        p_start = 1'b0;
        p_pins  = rec[CtlW + PinW +: PinW];
        if (!Compact) p_pins[PThr +: 16] = thr_prev;
        @(negedge clk);
        p_pins[PThr +: 16] = rec[CtlW + PinW + PThr +: 16];
        repeat (32'(rec[CGap +: 2]) - 1) @(negedge clk);
      end
      p_start = 1'b1;                                     // the vector
      p_pins  = rec[CtlW +: PinW];
      if (!Compact && rec[CPre +: 2] == 2'd0) p_pins[PThr +: 16] = thr_prev;   // back to back: thr_i late
      @(negedge clk);
      if (busy_o !== 1'b1 || done_o !== 1'b0) fail(gi, 3'd1);
      p_pins[5:3]  = rec[CSsec +: 3];                     // start_i held high: ignored while busy
      p_pins[21:6] = rec[CSang +: 16];
      p_pins[PThr +: 16] = rec[CtlW + PThr +: 16];
      // to 1 ns after the edge that must raise done_o (edge counts, then constant delays)
      rest = 32'(latency_i) - 1;                          // rising edges to the one that must raise done_o
      if (rec[CMid]) begin                                // scramble once more mid-computation
        mid = 32'(rec[CMk +: 9]);                         // 2 ns after falling edge k
        repeat (mid) @(negedge clk);
        #2;
        p_start      = rec[CMst];
        p_pins[5:3]  = rec[CMsec +: 3];
        p_pins[21:6] = rec[CMang +: 16];
        rest = rest - mid;
      end
      repeat (rest) @(posedge clk);
      #1;                                                 // 1 ns after it
      for (int ph = 0; ph < 3; ph++) exp_cmp[ph * CntWidth +: CntWidth] = rec[CEc + 16 * ph +: CntWidth];
      if (outputs() !== {1'b0, 1'b1, rec[CEsec +: 3], exp_cmp, rec[CEsat], rec[CEerr]}) fail(gi, 3'd2);
      for (int ph = 0; ph < 3; ph++) car_exp[ph * EW +: EW] = rec[CEcar + 16 * ph +: EW];
      car_idx = gi;
      car_cnt = 2;                                        // carry_o at done_o + 2 (the block above)
      @(negedge clk);                                     // middle of the done cycle
    end
    p_start = 1'b0;
    p_abort = 1'b0;
    thr_prev = p_pins[PThr +: 16];
    p_pins  = {PinW{1'b0}};
    if (!Compact) p_pins[PThr +: 16] = thr_prev;          // (the last vector's carry limit: header)
    @(negedge clk);
    @(negedge clk);                                       // (after the last carry_o check)
    playing    = 1'b0;
    play_end_o = !play_end_o;
  end

endmodule

`default_nettype wire
