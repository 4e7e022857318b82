// SPDX-License-Identifier: Apache-2.0
// svpwm_ice40_regs: the MINIMAL register set of the iCE40 board designs (see fpga/ice40/README.md).
// It is a stop-gap to be replaced by the SystemRDL register map; addresses are 8-bit, data 32-bit.
//   0x00 ID      RO  0x5356_5057 ("SVPW")
//   0x01 VERSION RO  0x0001_0000 (minimal register set 1.0)
//   0x02 CONFIG  RO  {PhaseWidth, FreqWidth, CntWidth, DtWidth} one byte each, MSB first
//   0x03 CLK_HZ  RO  core clock in Hz
//   0x04 CTRL    RW  [0] en; [1] fault_clr (write 1 clears the fault latch, reads 0)
//   0x05 FREQ    RW  signed frequency word (FreqWidth bits, read sign-extended)
//   0x06 M       RW  modulation index UQ1.15 (16 bits)
//   0x07 PERIOD  RW  half carrier period in clocks (CntWidth bits)
//   0x08 DT      RW  dead time in clocks (DtWidth bits)
//   0x09 STATUS  RO  [0] running [1] sat [2] period_clamp [3] fault latched [4] fault pin
//                    [10:8] sector
//   other        RO  0 (writes ignored)
// A fault (fault_i high) latches, clears CTRL.en and holds the gates off until fault_clr.
`default_nettype none

module svpwm_ice40_regs #(
  parameter int          CntWidth   = 16,
  parameter int          PhaseWidth = 34,
  parameter int          FreqWidth  = 24,
  parameter int          DtWidth    = 10,
  parameter int          ClkHz      = 48_000_000,
  parameter int          PeriodInit = 1536,
  parameter int          DtInit     = 48
) (
  input  wire                         clk_i,
  input  wire                         rst_ni,
  input  wire                         wr_i,
  input  wire  [7:0]                  addr_i,
  input  wire  [31:0]                 wdata_i,
  output logic [31:0]                 rdata_o,
  input  wire                         fault_i,        // synchronised fault request, 1 = fault
  // to / from the core
  output logic                        en_o,
  output logic signed [FreqWidth-1:0] freq_o,
  output logic [15:0]                 m_o,
  output logic [CntWidth-1:0]         period_o,
  output logic [DtWidth-1:0]          dt_o,
  input  wire                         running_i,
  input  wire                         m_clamp_i,
  input  wire                         period_clamp_i,
  input  wire  [2:0]                  sector_i,
  output logic                        fault_o         // fault latched
);
  localparam logic [7:0] AId = 8'h00, AVersion = 8'h01, AConfig = 8'h02, AClkHz = 8'h03,
                         ACtrl = 8'h04, AFreq = 8'h05, AM = 8'h06, APeriod = 8'h07, ADt = 8'h08,
                         AStatus = 8'h09;

  logic ctrl_en_q, fault_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      ctrl_en_q <= 1'b0;
      fault_q   <= 1'b0;
      freq_o    <= '0;
      m_o       <= '0;
      period_o  <= CntWidth'(PeriodInit);
      dt_o      <= DtWidth'(DtInit);
    end else begin
      if (wr_i) begin
        unique case (addr_i)
          ACtrl: begin
            ctrl_en_q <= wdata_i[0];
            if (wdata_i[1]) fault_q <= 1'b0;
          end
          AFreq:   freq_o   <= wdata_i[FreqWidth-1:0];
          AM:      m_o      <= wdata_i[15:0];
          APeriod: period_o <= wdata_i[CntWidth-1:0];
          ADt:     dt_o     <= wdata_i[DtWidth-1:0];
          default: ;
        endcase
      end
      if (fault_i) begin                // a fault wins over any write: latch it, stop
        fault_q   <= 1'b1;
        ctrl_en_q <= 1'b0;
      end
    end
  end

  assign en_o    = ctrl_en_q && !fault_q;
  assign fault_o = fault_q;

  always_comb begin
    unique case (addr_i)
      AId:      rdata_o = 32'h5356_5057;
      AVersion: rdata_o = 32'h0001_0000;
      AConfig:  rdata_o = {8'(PhaseWidth), 8'(FreqWidth), 8'(CntWidth), 8'(DtWidth)};
      AClkHz:   rdata_o = 32'(ClkHz);
      ACtrl:    rdata_o = {31'd0, ctrl_en_q};
      AFreq:    rdata_o = 32'(freq_o);          // sign-extended
      AM:       rdata_o = {16'd0, m_o};
      APeriod:  rdata_o = 32'(period_o);
      ADt:      rdata_o = 32'(dt_o);
      AStatus:  rdata_o = {21'd0, sector_i, 3'd0, fault_i, fault_q, period_clamp_i, m_clamp_i, running_i};
      default:  rdata_o = '0;
    endcase
  end
endmodule

`default_nettype wire
