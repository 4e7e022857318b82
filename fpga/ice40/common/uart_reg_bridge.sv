// SPDX-License-Identifier: Apache-2.0
// uart_reg_bridge: framed register protocol over a UART byte stream -> 8-bit address, 32-bit data bus.
// Frames (all bytes 8N1; chk makes the byte sum of the whole frame 0 mod 256, chk = -sum(preceding)):
//   write:  0x57 'W', addr, d0, d1, d2, d3 (LSB first), chk  ->  reply 0x4B 'K' after the write
//   read:   0x52 'R', addr, chk                              ->  reply d0, d1, d2, d3, chk (reply sum 0)
//   a complete frame with a bad checksum                     ->  reply 0x4E 'N', no register access
// Any other byte where a frame must start is ignored (the parser re-synchronises on 'W' / 'R'), a UART
// framing error aborts the frame, and a frame whose next byte does not arrive within TimeoutBits bit
// times of the previous one is dropped. Only a complete frame with a good checksum writes, so a
// malformed or truncated frame never changes a register. Bytes received while a reply is being sent
// are ignored: the host waits for the reply before the next frame.
`default_nettype none

module uart_reg_bridge #(
  parameter int ClksPerBit  = 417,     // 48 MHz / 115200
  parameter int TimeoutBits = 1000     // inter-byte timeout in bit times (8.7 ms at 115200 baud)
) (
  input  wire         clk_i,
  input  wire         rst_ni,
  input  wire         rx_i,            // UART from the host
  output logic        tx_o,            // UART to the host
  output logic        wr_o,            // one-clock register write strobe
  output logic [7:0]  addr_o,          // register address (valid with wr_o and for rdata_i)
  output logic [31:0] wdata_o,
  input  wire  [31:0] rdata_i          // read data of addr_o, combinational
);
  localparam logic [7:0] CmdWrite = 8'h57, CmdRead = 8'h52, RspAck = 8'h4B, RspNak = 8'h4E;
  localparam int TimeoutClks = ClksPerBit * TimeoutBits;
  localparam int TW = $clog2(TimeoutClks + 1);

  logic [7:0] rx_data;
  logic       rx_valid, rx_ferr;

  uart_rx #(.ClksPerBit(ClksPerBit)) u_rx (
    .clk_i       (clk_i),
    .rst_ni      (rst_ni),
    .rx_i        (rx_i),
    .data_o      (rx_data),
    .valid_o     (rx_valid),
    .frame_err_o (rx_ferr)
  );

  logic [7:0] tx_data;
  logic       tx_valid, tx_ready;

  uart_tx #(.ClksPerBit(ClksPerBit)) u_tx (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .data_i  (tx_data),
    .valid_i (tx_valid),
    .ready_o (tx_ready),
    .tx_o    (tx_o)
  );

  typedef enum logic [2:0] {SIdle, SAddr, SData, SChk, SReply} state_e;
  state_e      st_q;
  logic        is_wr_q;
  logic [1:0]  n_q;                 // data byte index / reply byte index
  logic [7:0]  sum_q;               // running byte sum of the frame
  logic [31:0] data_q;              // write data, later the read reply
  logic [2:0]  left_q;              // reply bytes still to send
  logic [TW-1:0] to_q;              // inter-byte timeout counter

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      st_q     <= SIdle;
      is_wr_q  <= 1'b0;
      n_q      <= '0;
      sum_q    <= '0;
      data_q   <= '0;
      left_q   <= '0;
      to_q     <= '0;
      addr_o   <= '0;
      wr_o     <= 1'b0;
      tx_valid <= 1'b0;
      tx_data  <= '0;
    end else begin
      wr_o     <= 1'b0;
      tx_valid <= 1'b0;
      if (st_q != SIdle && st_q != SReply) to_q <= to_q + 1'b1;
      if (rx_valid) to_q <= '0;

      unique case (st_q)
        SIdle: if (rx_valid && (rx_data == CmdWrite || rx_data == CmdRead)) begin
          st_q    <= SAddr;
          is_wr_q <= (rx_data == CmdWrite);
          sum_q   <= rx_data;
        end
        SAddr: if (rx_valid) begin
          addr_o <= rx_data;
          sum_q  <= sum_q + rx_data;
          n_q    <= '0;
          st_q   <= is_wr_q ? SData : SChk;
        end
        SData: if (rx_valid) begin
          data_q <= {rx_data, data_q[31:8]};      // LSB first
          sum_q  <= sum_q + rx_data;
          n_q    <= n_q + 1'b1;
          if (n_q == 2'd3) st_q <= SChk;
        end
        SChk: if (rx_valid) begin
          st_q <= SReply;
          if (sum_q + rx_data != 8'd0) begin
            tx_data  <= RspNak;                  // bad checksum: answer NAK, touch nothing
            tx_valid <= 1'b1;
            left_q   <= 3'd0;
          end else if (is_wr_q) begin
            wr_o     <= 1'b1;
            tx_data  <= RspAck;
            tx_valid <= 1'b1;
            left_q   <= 3'd0;
          end else begin
            data_q   <= rdata_i;                 // sample the read data, send 4 bytes + chk
            left_q   <= 3'd5;
            sum_q    <= '0;
          end
        end
        default: begin                           // SReply
          if (!tx_valid && tx_ready) begin
            if (left_q == 3'd0) st_q <= SIdle;
            else begin
              tx_valid <= 1'b1;
              left_q   <= left_q - 1'b1;
              if (left_q == 3'd1) tx_data <= 8'd0 - sum_q;
              else begin
                tx_data <= data_q[7:0];
                sum_q   <= sum_q + data_q[7:0];
                data_q  <= {8'd0, data_q[31:8]};
              end
            end
          end
        end
      endcase

      // truncated frame (timeout) or a UART framing error mid-frame: drop the frame
      if (st_q != SIdle && st_q != SReply && !rx_valid &&
          (rx_ferr || to_q == TW'(TimeoutClks))) begin
        st_q <= SIdle;
        to_q <= '0;
      end
    end
  end

  assign wdata_o = data_q;
endmodule

`default_nettype wire
