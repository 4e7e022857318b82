// SPDX-License-Identifier: Apache-2.0
// svpwm_duty_lite: small serial duty calculator of the compact core (FREQ mode only, continuous SVPWM,
// no DSP): sector + in-sector angle + magnitude m -> three snapped compare values, bit-exact with
// model/svpwm_model/fixed.py: snap_min_pulse(dwell_compare(sector, hex_clamp(duties(a16, m)), P), P, thr).
//   sines   sb = sin(theta'), sa = sin(60 deg - theta') by linear interpolation of the 0..60 deg sine_rom
//           (AVR495 sec. 4.2/6), duties T1 = m sa, T2 = m sb (Minas eq. (4)), each (m s + 2^14) >> 15
//   clamp   T1 + T2 > 1: q = floor(min(T1, T2) 2^16 / (T1 + T2)), the other 1 - q (Minas eq. (5)), cap 0xFFFF
//   compare A = (T1 P) >> 8, B = (T2 P) >> 8, C = ((P + 1) 2^8 +- A +- B) >> 9 per AVR495 Table 4-3
//   snap    minimum-pulse rule on each C with thr = dead time + minimum pulse (as rtl/svpwm_minpulse.sv)
// Architecture: a microcoded accumulator machine, one operation per clock on one W-bit adder:
//   sum = A + B + cin,  A = inv ^ (ACC >>> 1  or  {ACC, serial bit} << 1),  B = RAM[ra] | ROM or X (15:0)
//   ACC <- sum, hold or 0; the RAM writes ACC, MQ loads ACC (so ACC and the adder share logic cells).
// The operands live in a 32-word RAM (2 block RAMs) whose read port is the only wide B source besides the
// sine ROM and X, so no register has a wide multiplexer; a conditional read ORs a condition into the low
// address bits (a multiplicand or its zero partner, +-D, min(T1, T2), a snapped value ...). A microcode
// ROM (3 block RAMs, built at elaboration by ucode_word(); no hand-typed table) holds one 48-bit control
// word per step, addressed by the step counter. m, the angle fraction and thr are written into three
// small block RAMs when idle and read one bit per step (multiplier bits, thr shifted into ACC). Operations:
//   R-mode multiply step  ACC <- (ACC >>> 1) + y_k X   (y_k selects RAM word X or its zero partner):
//                         after n steps ACC = floor((ACC_0 + 2 X y) / 2^n)
//   L-mode divide step    ACC <- 2 ACC -+ D by the sign of ACC (non-restoring); quotient bits into X
//   add / subtract        one L step doubles ACC, an R step then adds B to +-ACC (inv, cin)
//   compare               sign of the sum latched into a flag, ACC held; the flags select RAM words
// Registers besides ACC: MQ (multiplier of the products, then C_a), X (P, then the quotient), the ROM
// index, the sector and six flags. Block RAMs: 8 besides sine_rom (microcode 3, operands 2, serial bits 3).
// Parameters: CntWidth - period / compare width (8..16); DtWidth - thr_i is DtWidth + 1 bits.
// Latency: Latency = 225 clocks from start_i to done_o, fixed (independent of the data and of the
// parameters); outputs hold until the next done_o (also across abort_i, which returns to idle without
// done_o); the done cycle is idle, so back-to-back starts work. Restrictions: period_i >= 2 * thr_i
// (svpwm_core clamps); start_i is ignored while busy_o; sector_i 0..5.
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

  localparam int TW = DtWidth + 1;          // thr width
  // adder width: 2 (T1 + T2) < 2^19 and the remainder of the division need 20 bits (signed);
  // (P + 1) 2^9 +- 2K needs CntWidth + 10
  localparam int W  = (CntWidth + 10 > 20) ? CntWidth + 10 : 20;

  if (CntWidth < 8 || CntWidth > 16) begin : gen_bad_width
`ifdef __ICARUS__  // Icarus 11 has no elaboration-time tasks: at time 0
    initial $fatal(1, "svpwm_duty_lite: CntWidth must be 8..16, got %0d (%m)", CntWidth);
`else              // at elaboration (Yosys formats $display only, then stops at $error)
    initial $display("svpwm_duty_lite: CntWidth must be 8..16, got %0d (%m)", CntWidth);
    $error("svpwm_duty_lite: CntWidth must be 8..16, got %0d", CntWidth);
`endif
  end
  if (TW > CntWidth) begin : gen_bad_dt
`ifdef __ICARUS__  // Icarus 11 has no elaboration-time tasks: at time 0
    initial $fatal(1, "svpwm_duty_lite: need DtWidth + 1 <= CntWidth, got %0d / %0d (%m)", DtWidth,
                   CntWidth);
`else              // at elaboration (Yosys formats $display only, then stops at $error)
    initial $display("svpwm_duty_lite: need DtWidth + 1 <= CntWidth, got %0d / %0d (%m)", DtWidth,
                     CntWidth);
    $error("svpwm_duty_lite: need DtWidth + 1 <= CntWidth, got %0d / %0d", DtWidth, CntWidth);
`endif
  end

  // ---- schedule (step numbers; step 1 clears ACC and is also the idle word). A result is written to
  // the RAM (or loaded into MQ) from ACC, i.e. in the step after the one that computes it.
  //   SPrep   10  P (from X), P << 7 (multiplicand of the products), (P + 1) 2^8      -> P1, P7, BASE
  //   SThr    16  16 - TW waits, then thr shifted into ACC MSB first (serial bits)
  //   SHalf   13  hthr = (thr + 1) >> 1, P - hthr, hhthr = (hthr + 1) >> 1, P - hhthr -> THR, HTHR, PH, PHH
  //   SIntB   15  e1 = R[i+1] - R[i]; 256 + 8 steps e1 * fr; + R[i]: sb              -> SB
  //   SIntA   15  e2 = R[255-i] - R[256-i]; 254 + 8 steps e2 * fr; + R[256-i]: sa    -> SA
  //   SDuty   35  2^15 + 16 steps sa * m -> T1; 2^15 + 16 steps sb * m -> T2
  //   SClamp   8  first = T1 <= T2, s = T1 + T2, sat = s > 2^16, -s, ACC = min(T1, T2)
  //   SDiv    16  q = floor(min 2^16 / D), D = sat ? s : 2^16 (q = min when not saturated)
  //   SProd   47  other = cap((sat ? 2^16 : s) - q); Q8 = (q P) >> 8, O8 = (other P) >> 8 (16 steps
  //               each, multiplier MQ, multiplicand P << 7); 2S = 2 (Q8 + O8), -2Dd = 2 (Q8 - O8)
  //   SPhase  47  per phase: ACC = 2K (2S or -2Dd, Table 4-3 code), X = (P + 1) 2^8 +- K, 8 shifts:
  //               ACC >>> 1 = c = X >> 9; compares c < thr, c < hthr, c > P - hthr, c > P - hhthr;
  //               snapped value (c, 0, thr, P or P - hthr) -> MQ (a), RAM CB (b), ACC (c)
  //   SDone    1  cmp <= {ACC, CB, MQ}, done_o next clock
  localparam int SPrep   = 2;
  localparam int SThr    = SPrep + 10;
  localparam int SHalf   = SThr + 16;
  localparam int SIntB   = SHalf + 13;
  localparam int SIntA   = SIntB + 15;
  localparam int SDuty   = SIntA + 15;
  localparam int SClamp  = SDuty + 35;
  localparam int SDiv    = SClamp + 8;
  localparam int SProd   = SDiv + 16;
  localparam int SPhase  = SProd + 47;
  localparam int SDone   = SPhase + 47;
  localparam int Latency = SDone + 1;       // clocks start_i -> done_o (model LITE_DUTY_LATENCY)
  localparam int StW     = $clog2(Latency); // step counter width (microcode address)
  if (StW != 8) begin : gen_bad_schedule
`ifdef __ICARUS__  // Icarus 11 has no elaboration-time tasks: at time 0
    initial $fatal(1, "svpwm_duty_lite: the ucode ROM has 256 words, the schedule %0d steps (%m)",
                   Latency);
`else              // at elaboration (Yosys formats $display only, then stops at $error)
    initial $display("svpwm_duty_lite: the ucode ROM has 256 words, the schedule %0d steps (%m)",
                     Latency);
    $error("svpwm_duty_lite: the ucode ROM has 256 words, the schedule %0d steps", Latency);
`endif
  end

  // ---- RAM map (32 words). Conditional reads OR a condition into the low address bits: a multiplicand
  // at an odd address with its zero partner below it; blocks of 2 / 4 words for the other choices.
  localparam logic [4:0] AZero = 5'd0,  AE  = 5'd1,  ASa  = 5'd3,  ASb = 5'd5,  AP7 = 5'd7;
  localparam logic [4:0] ACb   = 5'd1;                              // C_b (the E slot is free by then)
  localparam logic [4:0] ACap  = 5'd8;                              // {0, -1}: cap at 0xFFFF
  localparam logic [4:0] ARom  = 5'd10;                             // {0, sin 60 deg}: ROM address 256
  localparam logic [4:0] ARep  = 5'd12;                             // {0, thr, P, P - hthr}: snap values
  localparam logic [4:0] AThr  = 5'd13, AP1 = 5'd14, APh = 5'd15;
  localparam logic [4:0] ADiv  = 5'd16;                             // {-2^16, -s, 2^16, s}
  localparam logic [4:0] ANegS = 5'd17, AC64K = 5'd18, AS = 5'd19;
  localparam logic [4:0] AT    = 5'd20, AT1 = 5'd21;                // {T2, T1}: min by `first`
  localparam logic [4:0] AK    = 5'd22, AKnd = 5'd23;               // {2S, -2Dd}
  localparam logic [4:0] AC256 = 5'd24, AC254 = 5'd25, AC32K = 5'd26;
  localparam logic [4:0] AOther = 5'd27, AQ8x2 = 5'd28, AHthr = 5'd29, APhh = 5'd30, ABase = 5'd31;
  localparam int         RamWords = 32;
  localparam logic [15:0] Sin60 = 16'd56756;                        // sine_rom entry 256 (sin 60 deg)

  function automatic logic [W-1:0] ram_init(input int k);
    unique case (k)
      9:       ram_init = '1;                        // -1
      11:      ram_init = W'(Sin60);
      16:      ram_init = W'(-32'sh1_0000);          // -2^16
      18:      ram_init = W'(32'h1_0000);            // 2^16
      24:      ram_init = W'(256);                   // sb rounding 128, doubled
      25:      ram_init = W'(254);                   // sa rounding 127, doubled
      26:      ram_init = W'(32'h8000);              // duty rounding 2^14, doubled
      default: ram_init = '0;
    endcase
  endfunction

  // ---- microcode word (48 bits, 3 block RAMs) --------------------------------------------------------
  // Bits 17:0 control the step itself; bits 33:18 (from FNext) are the reads, the A-operand inversion and
  // the carry-in of the NEXT step, so that the block RAMs can register the addresses and inv / cin can be
  // registered; bits 40:34 the serial-bit read whose data is visible in the next step:
  // word k = {serial read for step k + 1, next-step fields of step k + 1, own fields of step k}.
  //   own:    l, acc[1:0], xsel, we, wa[4:0], op[7:0] (one-hot register operations)
  //   next:   rom[1:0], cond[3:0], ra[4:0], ph[1:0], inv[1:0], cin
  //   serial: sel[2:0] (one-hot m, fr, thr; none reads 0), bit[3:0]
  localparam int FNext = 18;
  localparam int FSer  = 34;
  localparam int UcW   = 48;
  // A operand inversion
  localparam logic [1:0] InvNo = 2'd0, InvYes = 2'd1, InvNeg = 2'd2;
  // ACC
  localparam logic [1:0] AccSum = 2'd0, AccHold = 2'd1, AccClr = 2'd2, AccSnap = 2'd3;
  // register operations (bit numbers in op)
  localparam int OMqSh = 0, OMqLd = 1, OXShl = 2, OFlip = 3, OFirst = 4, OSat = 5, OFlag = 6, ODone = 7;
  // read conditions (ORed into the RAM address bits 1:0)
  localparam logic [3:0] CNone = 4'd0, CSer = 4'd1, CMq = 4'd3, CFirst = 4'd4, CDiv = 4'd5;
  localparam logic [3:0] CNsat = 4'd6, CCap = 4'd7, CKsel = 4'd8, CRep = 4'd9, CRom = 4'd10;
  // sine ROM read: off (address 0, reads 0), i, i + 1 (i = index, or 255 - index once flipped)
  localparam logic [1:0] RomOff = 2'd0, RomI = 2'd1, RomI1 = 2'd2;

  // serial bits: sel (one-hot: m, fr, thr) and bit number
  localparam logic [2:0] SerM = 3'b001, SerFr = 3'b010, SerThr = 3'b100;

  // the serial bit step k consumes: thr bits shifted into ACC (MSB first), multiplier bits (LSB first) of
  // the multiplications by fr and m -- a multiplier bit selects the RAM word read in step k, so it is
  // needed one step earlier; {sel, bit}, 0 if none
  function automatic logic [6:0] ser_use(input int k);
    int j;
    ser_use = '0;
    j = k - SThr - (16 - TW);
    if (j >= 0 && j < TW) ser_use = {SerThr, 4'(TW - 1 - j)};
    j = k + 1 - SIntB;
    if (j >= 5 && j < 13) ser_use = {SerFr, 4'(j - 5)};
    j = k + 1 - SIntA;
    if (j >= 5 && j < 13) ser_use = {SerFr, 4'(j - 5)};
    j = k + 1 - SDuty;
    if (j >= 1 && j < 17) ser_use = {SerM, 4'(j - 1)};
    if (j >= 19 && j < 35) ser_use = {SerM, 4'(j - 19)};
  endfunction

  // one step: its own controls, reads, inversion and carry-in (ucode_word moves the last to the step before)
  function automatic logic [UcW-1:0] step(input int k);
    logic        l, cin, xsel, we;
    logic [1:0]  inv, acc, ph, rom;
    logic [3:0]  cond;
    logic [4:0]  ra, wa;
    logic [7:0]  op;
    int          j, p;
    l = 1'b0; inv = InvNo; cin = 1'b0; acc = AccSum; xsel = 1'b0; we = 1'b0; wa = AZero; op = '0;
    ph = 2'd0; ra = AZero; cond = CNone; rom = RomOff;
    if (k == 1) begin                                  // also the idle word
      acc = AccClr;
    end else if (k < SThr) begin
      j = k - SPrep;
      if (j == 0) begin                                // P
        xsel = 1'b1;
      end else if (j < 8) begin                        // P << j
        l = 1'b1;
        if (j == 1) begin
          we = 1'b1; wa = AP1;
        end
      end else if (j == 8) begin                       // (P << 8) + 256
        l = 1'b1; ra = AC256; we = 1'b1; wa = AP7;
      end else begin
        we = 1'b1; wa = ABase; acc = AccClr;
      end
    end else if (k < SHalf) begin                      // waits, then thr MSB first
      l = (k - SThr >= 16 - TW);
    end else if (k < SIntB) begin
      unique case (k - SHalf)
        0:       begin l = 1'b1; cin = 1'b1; we = 1'b1; wa = AThr; end   // 2 thr + 1
        1:       cin = 1'b1;                                           // thr + 1
        2:       ;                                                     // hthr
        3:       begin l = 1'b1; we = 1'b1; wa = AHthr; end            // 2 hthr
        4:       begin inv = InvYes; cin = 1'b1; ra = AP1; end         // P - hthr
        5:       begin l = 1'b1; we = 1'b1; wa = APh; end              // 2 (P - hthr)
        6:       begin inv = InvYes; cin = 1'b1; ra = AP1; end         // hthr
        7:       l = 1'b1;                                             // 2 hthr
        8:       cin = 1'b1;                                           // hthr + 1
        9:       ;                                                     // hhthr
        10:      l = 1'b1;                                             // 2 hhthr
        11:      begin inv = InvYes; cin = 1'b1; ra = AP1; end         // P - hhthr
        default: begin we = 1'b1; wa = APhh; acc = AccClr; end
      endcase
    end else if (k < SDuty) begin                      // sb, then sa (flipped index: 255 - i)
      p = (k < SIntA) ? 1 : 0;
      j = k - ((p != 0) ? SIntB : SIntA);
      if (j == 0) begin                                // R[i] / R[256-i]
        rom = (p != 0) ? RomI : RomI1; ra = ARom; cond = CRom;
      end else if (j == 1) begin
        l = 1'b1;
      end else if (j == 2) begin                       // R[i+1] - R[i] / R[255-i] - R[256-i]
        inv = InvYes; cin = 1'b1; rom = (p != 0) ? RomI1 : RomI; ra = ARom; cond = CRom;
      end else if (j == 3) begin
        we = 1'b1; wa = AE; acc = AccClr;
      end else if (j == 4) begin
        ra = (p != 0) ? AC256 : AC254;
      end else if (j < 13) begin
        ra = AE; cond = CSer;
        if (p != 0 && j == 12) op[OFlip] = 1'b1;       // the next reads use 255 - i
      end else if (j == 13) begin                      // + R[i] / + R[256-i]
        rom = (p != 0) ? RomI : RomI1; ra = ARom; cond = CRom;
      end else begin
        we = 1'b1; wa = (p != 0) ? ASb : ASa; acc = AccClr;
      end
    end else if (k < SClamp) begin                     // T1 = m sa, T2 = m sb
      j = k - SDuty;
      if (j == 0 || j == 18) begin
        ra = AC32K;
      end else if (j < 17) begin
        ra = ASa; cond = CSer;
      end else if (j == 17) begin
        we = 1'b1; wa = AT1; acc = AccClr;
      end else begin
        ra = ASb; cond = CSer;
      end
    end else if (k < SDiv) begin
      unique case (k - SClamp)
        0:       begin l = 1'b1; we = 1'b1; wa = AT; end                      // 2 T2
        1:       begin inv = InvYes; ra = AT1; acc = AccHold; op[OFirst] = 1'b1; end  // T1 - T2 - 1 < 0
        2:       ra = AT1;                                                    // s = T1 + T2
        3:       begin l = 1'b1; we = 1'b1; wa = AS; end                      // 2 s
        4:       begin inv = InvYes; cin = 1'b1; ra = AC64K; acc = AccHold; op[OSat] = 1'b1; end
        5:       begin inv = InvYes; cin = 1'b1; end                          // -s
        6:       begin we = 1'b1; wa = ANegS; acc = AccClr; end
        default: begin ra = AT; cond = CFirst; end                            // min(T1, T2)
      endcase
    end else if (k < SProd) begin                      // 2 rem -+ D
      l = 1'b1; ra = ADiv; cond = CDiv; op[OXShl] = 1'b1;
      if (k == SProd - 1) acc = AccClr;
    end else if (k < SPhase) begin
      j = k - SProd;
      if (j == 0) begin                                // q
        xsel = 1'b1;
      end else if (j == 1) begin                       // 2q; MQ = q
        l = 1'b1; op[OMqLd] = 1'b1;
      end else if (j == 2) begin                       // (sat ? 2^16 : s) - q
        inv = InvYes; cin = 1'b1; ra = AC64K; cond = CNsat;
      end else if (j == 3 || j == 22 || j == 44) begin
        l = 1'b1;
      end else if (j == 4) begin                       // capped at 0xFFFF
        ra = ACap; cond = CCap;
      end else if (j == 5) begin
        we = 1'b1; wa = AOther; acc = AccClr;
      end else if (j < 22 || (j > 25 && j < 42)) begin // multiply by MQ: Q8, then O8
        ra = AP7; cond = CMq; op[OMqSh] = 1'b1;
      end else if (j == 23) begin
        we = 1'b1; wa = AQ8x2; acc = AccClr;
      end else if (j == 24) begin
        ra = AOther;
      end else if (j == 25) begin                      // MQ = other
        op[OMqLd] = 1'b1; acc = AccClr;
      end else if (j == 42) begin                      // 2 O8 + 2 Q8 = 2S
        l = 1'b1; ra = AQ8x2;
      end else if (j == 43) begin                      // 2 Q8 - S = -Dd
        inv = InvYes; cin = 1'b1; ra = AQ8x2; we = 1'b1; wa = AK;
      end else if (j == 45) begin
        we = 1'b1; wa = AKnd; acc = AccClr;
      end                                              // 46: wait (-2Dd is readable from 47 on)
    end else if (k < SDone) begin
      p  = (k - SPhase) / 16;
      j  = (k - SPhase) % 16;
      ph = 2'(p);
      if (j == 0) begin                                // ACC = 2K
        ra = AK; cond = CKsel;
      end else if (j == 1) begin                       // (P + 1) 2^8 +- K
        inv = InvNeg; ra = ABase;
      end else if (j < 10) begin                       // >>> 8
      end else if (j < 14) begin                       // compares on c = ACC >>> 1, ACC held
        inv = InvYes; op[OFlag] = 1'b1; acc = AccHold;
        unique case (j)
          10:      ra = AThr;                          // thr - c - 1 < 0: not c < thr
          11:      ra = AHthr;
          12:      begin cin = 1'b1; ra = APh; end     // P - hthr - c < 0: c > P - hthr
          default: begin cin = 1'b1; ra = APhh; acc = AccSnap; end
        endcase
      end else if (j == 14) begin                      // snapped value: c (ACC kept) or a RAM word
        ra = ARep; cond = CRep;
      end else if (p == 0) begin                       // C_a -> MQ
        op[OMqLd] = 1'b1; acc = AccClr;
      end else begin                                   // C_b -> RAM
        we = 1'b1; wa = ACb; acc = AccClr;
      end
    end else if (k == SDone) begin
      ra = ACb; op[ODone] = 1'b1;
    end
    // a multiplicand read addresses its zero partner; the multiplier bit selects the word itself
    if (cond == CSer || cond == CMq) ra[0] = 1'b0;
    step = {14'd0, cin, inv, ph, ra, cond, rom, op, wa, we, xsel, acc, l};
  endfunction

  localparam logic [UcW-1:0] NextMask = ((UcW'(1) << FSer) - UcW'(1)) & ~((UcW'(1) << FNext) - UcW'(1));

  function automatic logic [UcW-1:0] ucode_word(input int k);
    ucode_word = (UcW'(ser_use(k + 1)) << FSer) | (step(k + 1) & NextMask) | (step(k) & ~NextMask);
  endfunction

  // ---- state -------------------------------------------------------------------------------------
  logic [StW-1:0]        st_d, st_q;            // step = microcode address
  logic                  idle_d, idle_q, done_d, done_q;
  logic [W-1:0]          acc_d, acc_q;          // accumulator
  logic [15:0]           mq_d, mq_q;            // multiplier: dwell times; then C_a
  logic [15:0]           x_d, x_q;              // P, then the quotient
  logic [7:0]            idx_d, idx_q;          // ROM index i
  logic                  flip_d, flip_q;        // read 255 - i
  logic [2:0]            sec_d, sec_q;
  logic                  first_d, first_q, sat_d, sat_q;
  logic [2:0]            fs_d, fs_q;            // signs of the last three snap compares
  logic                  inv_d, inv_q, cin_d, cin_q;
  logic [3*CntWidth-1:0] cmp_d, cmp_q;
  logic [2:0]            sector_out_d, sector_out_q;
  logic                  sat_out_d, sat_out_q;

  // ---- microcode ROM -------------------------------------------------------------------------------
  logic [UcW-1:0] ucode [256];
  logic [UcW-1:0] uc_q;

  // addressed by the step counter itself: address k holds the word of step k + 1, so uc_q is the word of
  // step st_q (and of step 1 while idle)
  initial begin
    for (int k = 0; k < 256; k++) ucode[k] = ucode_word(k + 1);
  end

  always_ff @(posedge clk_i) begin
    uc_q <= ucode[st_q];
  end

  logic       uc_l, uc_xsel, uc_we, uc_cin;
  logic [1:0] uc_acc, uc_rom, uc_ph, uc_inv;
  logic [2:0] uc_ssel;
  logic [3:0] uc_cond, uc_sbit;
  logic [4:0] uc_wa, uc_ra;
  logic [7:0] uc_op;
  logic [6:0] unused_uc;
  assign {unused_uc, uc_ssel, uc_sbit, uc_cin, uc_inv, uc_ph, uc_ra, uc_cond, uc_rom, uc_op, uc_wa, uc_we,
          uc_xsel, uc_acc, uc_l} = uc_q;

  // ---- serial bits: m, fr and thr, written into small block RAMs in every idle cycle (the last write is
  // the start cycle's), read one bit per clock; word 0 is never written and reads 0 ("no bit"). The write
  // address is {idle_q, bit}, not a constant, so that Yosys keeps the arrays as memories.
  (* ram_style = "block", no_rw_check *) logic ser_m [32];
  (* ram_style = "block", no_rw_check *) logic ser_f [32];
  (* ram_style = "block", no_rw_check *) logic ser_t [32];
  logic ser_m_q, ser_f_q, ser_t_q, ser;

  initial begin
    for (int k = 0; k < 32; k++) begin
      ser_m[k] = 1'b0;
      ser_f[k] = 1'b0;
      ser_t[k] = 1'b0;
    end
  end

  always_ff @(posedge clk_i) begin
    if (idle_q) begin
      for (int k = 0; k < 16; k++) ser_m[{idle_q, 4'(k)}] <= m_i[k];
      for (int k = 0; k < 8; k++)  ser_f[{idle_q, 4'(k)}] <= angle_i[k];
      for (int k = 0; k < TW; k++) ser_t[{idle_q, 4'(k)}] <= thr_i[k];
    end
    ser_m_q <= ser_m[{uc_ssel[0], uc_sbit}];
    ser_f_q <= ser_f[{uc_ssel[1], uc_sbit}];
    ser_t_q <= ser_t[{uc_ssel[2], uc_sbit}];
  end
  assign ser = ser_m_q | ser_f_q | ser_t_q;

  // ---- operand RAM ----------------------------------------------------------------------------------
  (* no_rw_check *) logic [W-1:0] ram [RamWords];
  logic [W-1:0] ram_q;
  logic [4:0]   ra_d;
  logic         ram_we;
  logic [W-1:0] sum;

  initial begin
    for (int k = 0; k < RamWords; k++) ram[k] = ram_init(k);
  end

  always_ff @(posedge clk_i) begin
    if (ram_we) ram[uc_wa] <= acc_q;
    ram_q <= ram[ra_d];
  end

  // ---- sine ROM: entries 0..255 (address 256 is read from the RAM instead) ---------------------------
  logic [8:0]  rom_sum;                         // i + inc or 255 - i + inc, 0..256 (0 when off)
  logic [8:0]  rom_addr;
  logic [15:0] rom_data;

  sine_rom u_rom (
    .clk_i  (clk_i),
    .addr_i (rom_addr),
    .data_o (rom_data)
  );

  assign rom_sum  = {1'b0, (idx_q ^ {8{flip_q}}) & {8{uc_rom != RomOff}}} + {8'd0, uc_rom == RomI1};
  assign rom_addr = {1'b0, rom_sum[7:0]};

  // ---- compare-value selection: AVR495 Table 4-3 ----------------------------------------------------
  // per phase: 0: +(A+B)  1: -(A+B)  2: +(A-B)  3: -(A-B), A = T1 P, B = T2 P

  logic [5:0] sel;
  logic [1:0] code;     // Table 4-3 code of the phase of the next step (uc_ph)
  logic       ksel;     // K = Dd (stored as -2Dd), else S
  logic       neg;      // the phase adds -K

  svpwm_sector_sel u_sel (          // generated from the model's SECTOR_SEL
    .sector_i (sec_q),
    .sel_o    (sel)
  );
  assign code = (uc_ph == 2'd0) ? sel[1:0] : (uc_ph == 2'd1) ? sel[3:2] : sel[5:4];
  assign ksel = code[1];
  // A - B = -Dd when T1 is the smaller dwell time (first); the word holds -2Dd
  assign neg  = code[1] ? !(code[0] ^ first_q) : code[0];

  // A-operand inversion and carry-in of the next step
  always_comb begin
    unique case (uc_inv)
      InvNo:   inv_d = 1'b0;
      InvYes:  inv_d = 1'b1;
      default: inv_d = neg;
    endcase
  end
  assign cin_d = uc_inv[1] ? inv_d : uc_cin;

  // ---- the adder: sum = A + B + cin ------------------------------------------------------------------
  logic [W-1:0] opa, opb;
  logic [W:0]   t;
  logic         sign;
  logic         unused_t0;

  // L: shift in the serial bit (thr serialisation; 0 otherwise), R: arithmetic shift
  assign opa = (uc_l ? {acc_q[W-2:0], ser} : {acc_q[W-1], acc_q[W-1:1]}) ^ {W{inv_q}};
  assign opb = ram_q | W'(uc_xsel ? x_q : rom_data);
  // one carry chain: the extra LSB column turns cin into the carry-in (its sum bit is discarded)
  assign t         = {opa, 1'b1} + {opb, cin_q};
  assign sum       = t[W:1];
  assign sign      = sum[W-1];
  assign unused_t0 = t[0];

  // ---- minimum-pulse snap (fixed.snap_min_pulse) from the compare signs: c < thr -> 0 or thr;
  // P - c < ceil(thr/2) -> P or P - ceil(thr/2), whichever is nearer. Requires P >= 2 thr, c <= P.
  logic f1, f2, f3, f4, snap;
  logic [1:0] rep;                              // RAM word of the snapped value: 0, thr, P, P - hthr
  assign f1   = !fs_q[2];                       // c < thr
  assign f2   = !fs_q[1];                       // c < hthr (2c < thr)
  assign f3   = fs_q[0];                        // c > P - hthr
  assign f4   = sign;                           // c > P - hhthr (2 (P - c) < hthr), this step
  assign snap = f1 || f3;
  assign rep  = {!f1 && f3, (f1 && !f2) || (!f1 && f3 && !f4)};

  // ---- next-step reads -------------------------------------------------------------------------------
  logic [1:0] rc;                               // condition bits ORed into the RAM address
  always_comb begin
    rc = 2'b00;
    unique case (uc_cond)
      CSer:    rc[0] = ser;
      CMq:     rc[0] = mq_d[0];
      CFirst:  rc[0] = first_q;
      CDiv:    rc    = {sign, sat_q};
      CNsat:   rc[0] = !sat_q;
      CCap:    rc[0] = sum[17];
      CKsel:   rc[0] = ksel;
      CRep:    rc    = rep;
      CRom:    rc[0] = rom_sum[8];
      default: ;
    endcase
  end
  assign ra_d   = uc_ra | {3'b000, rc};
  assign ram_we = uc_we && !idle_q;

  // ---- sequence ----------------------------------------------------------------------------------
  always_comb begin
    acc_d        = sum;
    mq_d         = mq_q;
    x_d          = x_q;
    idx_d        = idx_q;
    flip_d       = flip_q ^ uc_op[OFlip];
    sec_d        = sec_q;
    first_d      = uc_op[OFirst] ? sign : first_q;     // T1 - T2 - 1 < 0
    sat_d        = uc_op[OSat] ? sign : sat_q;         // 2^16 - s < 0
    fs_d         = uc_op[OFlag] ? {fs_q[1:0], sign} : fs_q;
    cmp_d        = cmp_q;
    sector_out_d = sector_out_q;
    sat_out_d    = sat_out_q;
    done_d       = uc_op[ODone] && !idle_q && !abort_i;
    unique case (uc_acc)
      AccHold: acc_d = acc_q;
      AccClr:  acc_d = '0;
      AccSnap: acc_d = snap ? '0 : acc_q;
      default: ;
    endcase
    if (uc_op[OMqSh]) mq_d = {1'b0, mq_q[15:1]};
    if (uc_op[OMqLd]) mq_d = acc_q[15:0];
    if (uc_op[OXShl]) x_d  = {x_q[14:0], !sign};          // quotient bit: new remainder >= 0
    if (idle_q) begin                   // idle: the input registers follow the inputs
      idx_d  = angle_i[15:8];
      flip_d = 1'b0;
      x_d    = 16'(period_i);
      sec_d  = sector_i;
    end
    if (done_d) begin
      cmp_d        = {acc_q[CntWidth-1:0], ram_q[CntWidth-1:0], mq_q[CntWidth-1:0]};
      sector_out_d = sec_q;
      sat_out_d    = sat_q;
    end
    if (abort_i || (idle_q && !start_i) || (!idle_q && uc_op[ODone])) begin
      st_d   = '0;
      idle_d = 1'b1;
    end else begin
      st_d   = st_q + StW'(1);          // idle: st_q = 0, so the first step is 1
      idle_d = 1'b0;
    end
  end

  // datapath registers: no reset (loaded before use)
  always_ff @(posedge clk_i) begin
    acc_q   <= acc_d;
    mq_q    <= mq_d;
    x_q     <= x_d;
    idx_q   <= idx_d;
    flip_q  <= flip_d;
    sec_q   <= sec_d;
    first_q <= first_d;
    sat_q   <= sat_d;
    fs_q    <= fs_d;
    inv_q   <= inv_d;
    cin_q   <= cin_d;
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      st_q         <= '0;
      idle_q       <= 1'b1;
      done_q       <= 1'b0;
      cmp_q        <= '0;
      sector_out_q <= '0;
      sat_out_q    <= 1'b0;
    end else begin
      st_q         <= st_d;
      idle_q       <= idle_d;
      done_q       <= done_d;
      cmp_q        <= cmp_d;
      sector_out_q <= sector_out_d;
      sat_out_q    <= sat_out_d;
    end
  end

  assign busy_o   = !idle_q;
  assign done_o   = done_q;
  assign sector_o = sector_out_q;
  assign cmp_o    = cmp_q;
  assign sat_o    = sat_out_q;

endmodule

`default_nettype wire
